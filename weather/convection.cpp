#include "weather/convection.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "weather/fast_math.h"
#include "weather/fast_math_sse.h"
#include "weather/physical_constants.h"
#include "weather/thermodynamics.h"

namespace firmament::weather {
namespace {

struct Thermals {
  float invRhoH, p0, tRef, deardorff, environment, inflowPerKelvin;
};

// The cloud base (LCL) of every cell: the dew point from Tetens inverted with logFast (dewPoint in
// thermodynamics.h; |error| < 1e-4 K against the double formula), then Espy. Also the parcel-table cell
// and the thermal's kinetic energy ½(w* + max(0, w_l) + s w)², computed exactly as the trigger does.
// (The scalar form: the cells after the last four, and targets without SSE2; applyConvection's SSE2
// loop does the same four cells at a time.)
// Restrict parameters: GCC trusts them here, not on pointers taken from vectors inside the caller.
void cloudBaseAndThermal(size_t n, const float* __restrict vapour, const float* __restrict anomalyT,
                         const float* __restrict heatFlux, const float* __restrict lift,
                         const float* __restrict updraft, const float* __restrict warming,
                         const ParcelTable::Indexer locate, const Thermals k, float* __restrict base,
                         int32_t* __restrict index, float* __restrict fractionA, float* __restrict fractionD,
                         float* __restrict kinetic) {
  const float eps = float(kEpsilon), espy = float(kLclMetresPerKelvin), invE0 = 1.0f / 610.78f;
  size_t c = 0;
  for (; c < n; ++c) {
    const float anomaly = anomalyT[c];
    const float mixing = vapour[c] * k.invRhoH;
    const float e = std::max(k.p0 * mixing / (eps + mixing), 1e-3f);
    const float x = std::min(logFast(e * invE0), 17.0f);
    const float dew = (17.27f * 273.15f - 35.85f * x) / (17.27f - x);
    const float lcl = espy * std::max(0.0f, k.tRef + anomaly - dew);
    base[c] = lcl;
    index[c] = locate(anomaly - warming[c], lcl * float(1.0 / kLclMetresPerKelvin), fractionA[c], fractionD[c]);
    const float heat = heatFlux[c];
    const float wStar = heat > 0.0f ? cbrtFast(k.deardorff * heat / (k.tRef + anomaly)) : 0.0f;
    const float inflow = std::clamp(1.0f + (anomaly - k.environment) * k.inflowPerKelvin, 0.0f, 1.0f);
    const float thermal = wStar + std::max(0.0f, lift[c]) + updraft[c] * inflow;
    kinetic[c] = 0.5f * thermal * thermal;
  }
}

// Cells the trigger must visit: those with an updraft, and those whose thermal pays the least CIN of
// their table cell where that cell has CAPE anywhere (a bound: the trigger decides with the interpolated
// values, so a cell left out is one it would have left unchanged). The table loads in a loop of their
// own: GCC vectorises gathers only in a loop without if-converted selects.
void mayTrigger(size_t n, const int32_t* __restrict index, const float* __restrict kinetic,
                const float* __restrict updraft, const float* __restrict maxCape, const float* __restrict minCin,
                uint8_t* __restrict active) {
  for (size_t c = 0; c < n; ++c) {
    const float cape = maxCape[index[c]], cin = minCin[index[c]];
    active[c] = uint8_t(((cape > 0.0f) & (kinetic[c] >= cin)) | (updraft[c] != 0.0f));
  }
}

}  // namespace

ConvectionResult applyConvection(WeatherState& s, const ParcelTable& table, const BoundaryLayer& layer,
                                 const ConvectionParameters& p, double dt_s, ColumnScratch& work) {
  constexpr float kCoreFraction = 0.1f, kUpdraftTime_s = 600.0f, kBuoyancyFrequency = 0.02f;
  constexpr float kMeanMoistLapse = 6.0e-3f;
  const float dt = float(dt_s);
  const float relax = 1.0f - std::exp(-dt / kUpdraftTime_s);
  const float rhoH = float(layer.massPerArea_kg_m2), invRhoH = 1.0f / rhoH;
  const float depth = float(layer.depth_m);
  const float tRef = float(layer.referenceTemperature_K);
  const float p0 = float(layer.surfacePressure_Pa);
  const float maxTop = float(p.tropopause_m) + 2000.0f;
  // g h/(ρ c_p) (heatCapacity is ρ c_p h per m²).
  const float deardorff = float(kGravity * layer.depth_m * layer.depth_m / layer.heatCapacity_J_m2_K);
  const float inflowPerKelvin = float(1.0 / p.coldPoolCutoff_K);
  const float exchangePerUpdraft = kCoreFraction / depth * dt;
  const float invScaleHeight = float(-1.0 / kPressureScaleHeight);
  const size_t n = s.cells();
  // The cold pool is cold against its surroundings: T′ relative to the domain mean.
  const float environment = float(sumField(s.temperature) / double(n));
  Field noWarming;
  if (!p.subsidenceWarming_K) noWarming.assign(n, 0.0f);
  const Field& warming = p.subsidenceWarming_K ? *p.subsidenceWarming_K : noWarming;
  const float ownShare = float(1.0 - p.inflowFraction);
  double updraftSum = 0.0, drawn = 0.0;
  // A node's four values interpolate as one vector (lanes: CAPE, v_c, LNB, LFC), the same arithmetic as
  // ParcelTable::lookup lane by lane; next to the edge of free convection the table's own lookup decides.
  using Lanes = float __attribute__((vector_size(16)));
  const ParcelTable::Node* nodes = table.nodes();
  const uint8_t* allFree = table.allFreeData();
  const float* minCin = table.minCinData();
  const float* maxCape = table.maxCapeData();
  const int32_t stride = table.rowStride();
  auto node = [nodes](int32_t i) {
    Lanes v;
    std::memcpy(&v, &nodes[i], sizeof v);
    return v;
  };
  size_t start = 0;
#if defined(__SSE2__)
  // Four cells at a time: the cloud base, the table position and the thermal (the scalar
  // cloudBaseAndThermal's operations per lane, fast_math_sse.h); the parcel's CAPE and v_c interpolated
  // from the table cell's corners (16-byte loads and a transpose per quantity; the same arithmetic as the
  // node interpolation), so that a block whose cells neither trigger nor have an updraft is done there;
  // else the scalar update below with its branches as selects. The updraft and drawn-vapour sums run in
  // pairs of double lanes (round-off against the scalar order).
  {
    using namespace sse;
    const ParcelTable::Indexer locate = table.indexer();
    const ParcelTable::Corners* capeCorners = table.capeCorners();
    const ParcelTable::Summary* summaries = table.summaries();
    const float eps = float(kEpsilon), invE0 = 1.0f / 610.78f;
    const F4 zero = _mm_setzero_ps(), one = set1(1.0f), half = set1(0.5f);
    const F4 invRhoHV = set1(invRhoH), p0V = set1(p0), epsV = set1(eps);
    const F4 perDegree = set1(float(1.0 / kLclMetresPerKelvin));
    const F4 maxA = set1(locate.maxA), maxD = set1(locate.maxD), rowLength = set1(float(locate.nAnomaly));
    const F4 relaxV = set1(relax), tRefV = set1(tRef), environmentV = set1(environment);
    __m128d updraftLo = _mm_setzero_pd(), updraftHi = _mm_setzero_pd(), drawnLo = _mm_setzero_pd(),
            drawnHi = _mm_setzero_pd();
    float* anomalyT = s.temperature.data();
    float* vapourW = s.vapour.data();
    float* cloudW = s.cloudWater.data();
    float* updraftW = s.updraft.data();
    float* cloudTopZ = s.cloudTop.data();
    float* convective = s.convectiveFraction.data();
    float* baseZ = s.cloudBase.data();
    const float* heatFlux = s.surfaceHeatFlux.data();
    const float* liftW = s.lift.data();
    const float* warmingK = warming.data();
    auto bilinear = [](const F4 c[4], F4 ta, F4 td) {
      const F4 lo = _mm_add_ps(c[0], _mm_mul_ps(ta, _mm_sub_ps(c[1], c[0])));
      const F4 hi = _mm_add_ps(c[2], _mm_mul_ps(ta, _mm_sub_ps(c[3], c[2])));
      return _mm_add_ps(lo, _mm_mul_ps(td, _mm_sub_ps(hi, lo)));
    };
    // In chunks of 256 cells: first the cloud base, table position and thermal of the chunk's cells, in
    // three loops without branches (each cell's quantities are long chains of dependent operations,
    // divisions among them; in short loops of their own the processor overlaps the chains of many
    // cells, which the per-block branches of the trigger keep it from doing), then the trigger and
    // update block by block.
    constexpr size_t kChunk = 256;
    alignas(16) float chunkTa[kChunk], chunkTd[kChunk], chunkKinetic[kChunk];
    alignas(16) int32_t chunkAt[kChunk];
    for (size_t chunk = 0; chunk + 4 <= n; chunk += kChunk) {
      const size_t end = std::min(n - n % 4, chunk + kChunk);
      for (size_t c = chunk; c < end; c += 4) {
        // The cloud base: ln(e/e₀), kept in chunkTa until the table position is computed.
        const F4 vapour = _mm_loadu_ps(vapourW + c);
        const F4 mixing = _mm_mul_ps(vapour, invRhoHV);
        const F4 e = maxStd(_mm_div_ps(_mm_mul_ps(p0V, mixing), _mm_add_ps(epsV, mixing)), set1(1e-3f));
        _mm_store_ps(chunkTa + (c - chunk), minStd(logFast(_mm_mul_ps(e, set1(invE0))), set1(17.0f)));
      }
      for (size_t c = chunk; c < end; c += 4) {
        const F4 anomaly = _mm_loadu_ps(anomalyT + c);
        const F4 x = _mm_load_ps(chunkTa + (c - chunk));
        const F4 dew =
            _mm_div_ps(_mm_sub_ps(set1(17.27f * 273.15f), _mm_mul_ps(set1(35.85f), x)), _mm_sub_ps(set1(17.27f), x));
        const F4 surfaceT = _mm_add_ps(tRefV, anomaly);
        const F4 lcl = _mm_mul_ps(set1(float(kLclMetresPerKelvin)), maxStd(zero, _mm_sub_ps(surfaceT, dew)));
        _mm_storeu_ps(baseZ + c, lcl);
      }
      // The table position and the thermal (a loop of its own: two shorter chains per cell than one).
      for (size_t c = chunk; c < end; c += 4) {
        const size_t k = c - chunk;
        const F4 anomaly = _mm_loadu_ps(anomalyT + c), lcl = _mm_loadu_ps(baseZ + c);
        const F4 surfaceT = _mm_add_ps(tRefV, anomaly);
        // ParcelTable::Indexer: clamped fractional position, cell index (in float: exact below 2²⁴).
        F4 fa = _mm_mul_ps(_mm_sub_ps(_mm_sub_ps(anomaly, _mm_loadu_ps(warmingK + c)), set1(ParcelTable::kMinAnomaly)),
                           set1(1.0f / ParcelTable::kAnomalyStep));
        F4 fd = _mm_mul_ps(_mm_mul_ps(lcl, perDegree), set1(1.0f / ParcelTable::kDepressionStep));
        fa = _mm_max_ps(zero, _mm_min_ps(maxA, fa));
        fd = _mm_max_ps(zero, _mm_min_ps(maxD, fd));
        const F4 a = _mm_cvtepi32_ps(_mm_cvttps_epi32(fa)), d = _mm_cvtepi32_ps(_mm_cvttps_epi32(fd));
        _mm_store_ps(chunkTa + k, _mm_sub_ps(fa, a));
        _mm_store_ps(chunkTd + k, _mm_sub_ps(fd, d));
        _mm_store_si128(reinterpret_cast<__m128i*>(chunkAt + k),
                        _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(d, rowLength), a)));
        // The thermal's kinetic energy.
        const F4 heat = _mm_loadu_ps(heatFlux + c);
        const F4 wStar =
            _mm_and_ps(_mm_cmpgt_ps(heat, zero), cbrtFast(_mm_div_ps(_mm_mul_ps(set1(deardorff), heat), surfaceT)));
        const F4 inflow =
            clampStd(_mm_add_ps(one, _mm_mul_ps(_mm_sub_ps(anomaly, environmentV), set1(inflowPerKelvin))), zero, one);
        const F4 thermal = _mm_add_ps(_mm_add_ps(wStar, maxStd(zero, _mm_loadu_ps(liftW + c))),
                                      _mm_mul_ps(_mm_loadu_ps(updraftW + c), inflow));
        _mm_store_ps(chunkKinetic + k, _mm_mul_ps(_mm_mul_ps(half, thermal), thermal));
      }
      for (start = chunk; start < end; start += 4) {
        const size_t c = start, k = c - chunk;
        const F4 anomaly = _mm_loadu_ps(anomalyT + c), vapour = _mm_loadu_ps(vapourW + c);
        const F4 lcl = _mm_loadu_ps(baseZ + c);
        const F4 ta = _mm_load_ps(chunkTa + k), td = _mm_load_ps(chunkTd + k), kineticV = _mm_load_ps(chunkKinetic + k);
        const int32_t* at = chunkAt + k;
        const F4 w0 = _mm_loadu_ps(updraftW + c);
        // The table cell's bounds and v_c's corners (32 bytes per cell), then the interpolated CIN; the
        // interpolated CAPE only where a cell may trigger (bounds passed, and the CIN paid or a corner
        // without free convection).
        F4 bounds[4], corners[4];
        for (int l = 0; l < 4; ++l) bounds[l] = _mm_load_ps(&summaries[at[l]].maxCape);
        _MM_TRANSPOSE4_PS(bounds[0], bounds[1], bounds[2], bounds[3]);  // max CAPE, min CIN, all free, −
        const F4 bound = _mm_and_ps(_mm_cmpgt_ps(bounds[0], zero), _mm_cmpge_ps(kineticV, bounds[1]));
        const F4 moving = _mm_cmpneq_ps(w0, zero);
        if (_mm_movemask_ps(_mm_or_ps(bound, moving)) == 0) continue;
        for (int l = 0; l < 4; ++l) corners[l] = _mm_load_ps(&summaries[at[l]].cinSpeed.c00);
        _MM_TRANSPOSE4_PS(corners[0], corners[1], corners[2], corners[3]);
        const F4 speed = bilinear(corners, ta, td);
        F4 cin = _mm_mul_ps(_mm_mul_ps(half, speed), speed);
        const F4 allFreeCorners = _mm_cmpgt_ps(bounds[2], zero);
        const F4 possible =
            _mm_and_ps(bound, _mm_or_ps(_mm_cmpge_ps(kineticV, cin),
                                        _mm_andnot_ps(allFreeCorners, _mm_castsi128_ps(_mm_set1_epi32(-1)))));
        if (_mm_movemask_ps(_mm_or_ps(possible, moving)) == 0) continue;
        for (int l = 0; l < 4; ++l) corners[l] = _mm_load_ps(&capeCorners[at[l]].c00);
        _MM_TRANSPOSE4_PS(corners[0], corners[1], corners[2], corners[3]);
        const F4 cape = bilinear(corners, ta, td);
        const F4 capeBound = _mm_and_ps(bound, _mm_cmpgt_ps(cape, zero));
        const F4 edge = _mm_andnot_ps(allFreeCorners, capeBound);  // not all corners free
        const int edgeLanes = _mm_movemask_ps(edge);
        // Next to the edge of free convection the table's lookup gives CIN and LNB (its CAPE is the same
        // interpolation as above).
        alignas(16) float edgeCin[4], edgeNeutral[4], fractionA[4], fractionD[4];
        if (edgeLanes) {
          _mm_store_ps(edgeCin, cin);
          _mm_store_ps(fractionA, ta);
          _mm_store_ps(fractionD, td);
          for (int l = 0; l < 4; ++l)
            if (edgeLanes & (1 << l)) {
              const ParcelProperties exact =
                  table.lookup(ParcelTable::Position{size_t(at[l]), fractionA[l], fractionD[l]});
              edgeCin[l] = exact.cin_J_kg;
              edgeNeutral[l] = exact.neutralBuoyancyLevel_m;
            }
          cin = _mm_load_ps(edgeCin);
        }
        const F4 triggered = _mm_and_ps(capeBound, _mm_cmpge_ps(kineticV, cin));
        // The updraft.
        const F4 target =
            _mm_and_ps(triggered, minStd(_mm_mul_ps(half, _mm_sqrt_ps(_mm_mul_ps(set1(2.0f), cape))), set1(60.0f)));
        F4 w = _mm_add_ps(w0, _mm_mul_ps(_mm_sub_ps(target, w0), relaxV));
        w = _mm_andnot_ps(_mm_cmplt_ps(w, set1(0.01f)), w);
        const F4 visited = _mm_or_ps(triggered, moving);
        w = select(visited, w, w0);
        _mm_storeu_ps(updraftW + c, w);
        const F4 wVisited = _mm_and_ps(visited, w);
        updraftLo = _mm_add_pd(updraftLo, _mm_cvtps_pd(wVisited));
        updraftHi = _mm_add_pd(updraftHi, _mm_cvtps_pd(_mm_movehl_ps(wVisited, wVisited)));
        const F4 runs = _mm_andnot_ps(_mm_cmplt_ps(w, set1(0.05f)), triggered);
        if (_mm_movemask_ps(runs) == 0) continue;
        // The level of neutral buoyancy: the nodes' interpolation, or the lookup's next to the edge.
        alignas(16) float neutralLanes[4];
        {
          _mm_store_ps(fractionA, ta);
          _mm_store_ps(fractionD, td);
          for (int l = 0; l < 4; ++l) {
            const float tal = fractionA[l], tdl = fractionD[l];
            const int32_t i = at[l];
            const Lanes v00 = node(i), v10 = node(i + 1), v01 = node(i + stride), v11 = node(i + stride + 1);
            const Lanes lo = v00 + tal * (v10 - v00), hi = v01 + tal * (v11 - v01), v = lo + tdl * (hi - lo);
            neutralLanes[l] = edgeLanes & (1 << l) ? edgeNeutral[l] : v[2];
          }
        }
        const F4 neutral = _mm_load_ps(neutralLanes);
        // Cloud top: grows at w toward the LNB plus overshoot; collapses toward it if above.
        const F4 topTarget =
            minStd(_mm_add_ps(maxStd(neutral, lcl), _mm_div_ps(w, set1(kBuoyancyFrequency))), set1(maxTop));
        const F4 oldTop = _mm_loadu_ps(cloudTopZ + c);
        F4 top = maxStd(oldTop, lcl);
        top = select(_mm_cmplt_ps(top, topTarget), minStd(topTarget, _mm_add_ps(top, _mm_mul_ps(w, set1(dt)))),
                     _mm_add_ps(topTarget, _mm_mul_ps(_mm_sub_ps(top, topTarget), _mm_sub_ps(one, relaxV))));
        _mm_storeu_ps(cloudTopZ + c, select(runs, top, oldTop));
        // Condensation into the core.
        const F4 cloud = _mm_loadu_ps(cloudW + c);
        const F4 lclTemperature =
            _mm_sub_ps(_mm_add_ps(tRefV, anomaly), _mm_mul_ps(set1(float(kDryAdiabaticLapseRate)), lcl));
        const F4 topTemperature = _mm_sub_ps(lclTemperature, _mm_mul_ps(set1(kMeanMoistLapse), _mm_sub_ps(top, lcl)));
        const F4 topPressure = _mm_mul_ps(set1(p0), expFast(_mm_mul_ps(top, set1(invScaleHeight))));
        const F4 remaining = _mm_mul_ps(set1(rhoH), saturationMixingRatioFast4(topTemperature, topPressure));
        const F4 exchange = oneMinusExpFast(_mm_mul_ps(set1(exchangePerUpdraft), w));
        const F4 dq = _mm_mul_ps(maxStd(zero, _mm_sub_ps(vapour, remaining)), exchange);
        const F4 newCloud = _mm_add_ps(cloud, dq),
                 newVapour = maxStd(zero, _mm_sub_ps(vapour, _mm_mul_ps(set1(ownShare), dq)));
        const __m128d gainLo = _mm_sub_pd(_mm_cvtps_pd(newCloud), _mm_cvtps_pd(cloud));
        const __m128d gainHi =
            _mm_sub_pd(_mm_cvtps_pd(_mm_movehl_ps(newCloud, newCloud)), _mm_cvtps_pd(_mm_movehl_ps(cloud, cloud)));
        const __m128d lossLo = _mm_sub_pd(_mm_cvtps_pd(vapour), _mm_cvtps_pd(newVapour));
        const __m128d lossHi =
            _mm_sub_pd(_mm_cvtps_pd(_mm_movehl_ps(vapour, vapour)), _mm_cvtps_pd(_mm_movehl_ps(newVapour, newVapour)));
        drawnLo =
            _mm_add_pd(drawnLo, _mm_and_pd(_mm_castps_pd(_mm_unpacklo_ps(runs, runs)), _mm_sub_pd(gainLo, lossLo)));
        drawnHi =
            _mm_add_pd(drawnHi, _mm_and_pd(_mm_castps_pd(_mm_unpackhi_ps(runs, runs)), _mm_sub_pd(gainHi, lossHi)));
        _mm_storeu_ps(cloudW + c, select(runs, newCloud, cloud));
        _mm_storeu_ps(vapourW + c, select(runs, newVapour, vapour));
        const F4 conv = _mm_loadu_ps(convective + c), total = _mm_add_ps(cloud, dq);
        const F4 mixed =
            select(_mm_cmpgt_ps(total, zero), _mm_div_ps(_mm_add_ps(_mm_mul_ps(conv, cloud), dq), total), one);
        _mm_storeu_ps(convective + c, select(runs, mixed, conv));
        // The exchanged air is replaced by the surroundings': a warm anomaly relaxes toward them.
        const F4 vented =
            _mm_add_ps(environmentV, _mm_mul_ps(_mm_sub_ps(anomaly, environmentV), _mm_sub_ps(one, exchange)));
        _mm_storeu_ps(anomalyT + c, select(_mm_and_ps(runs, _mm_cmpgt_ps(anomaly, environmentV)), vented, anomaly));
      }
    }
    alignas(16) double parts[8];
    _mm_store_pd(parts, updraftLo);
    _mm_store_pd(parts + 2, updraftHi);
    _mm_store_pd(parts + 4, drawnLo);
    _mm_store_pd(parts + 6, drawnHi);
    updraftSum = (parts[0] + parts[1]) + (parts[2] + parts[3]);
    drawn = (parts[4] + parts[5]) + (parts[6] + parts[7]);
  }
#endif
  // The remaining cells (all of them without SSE2): the first pass over them, in loops that vectorise
  // (the cloud base, and which cells the second must visit), then the update of the marked ones.
  const size_t rest = n - start;
  work.active.resize(rest);
  work.index.resize(rest);
  for (Field& f : work.value) f.resize(rest);
  float* __restrict kinetic = work.value[0].data();
  float* __restrict fractionA = work.value[1].data();
  float* __restrict fractionD = work.value[2].data();
  const int32_t* index = work.index.data();
  Thermals thermals{invRhoH, p0, tRef, deardorff, environment, inflowPerKelvin};
  cloudBaseAndThermal(rest, s.vapour.data() + start, s.temperature.data() + start, s.surfaceHeatFlux.data() + start,
                      s.lift.data() + start, s.updraft.data() + start, warming.data() + start, table.indexer(),
                      thermals, s.cloudBase.data() + start, work.index.data(), fractionA, fractionD, kinetic);
  mayTrigger(rest, work.index.data(), kinetic, s.updraft.data() + start, maxCape, minCin, work.active.data());
  forEachActiveCell(work.active, [&](size_t k) {
    const size_t c = start + k;
    const float anomaly = s.temperature[c];
    const float surfaceT = tRef + anomaly;
    const float vapour = s.vapour[c];
    const float lcl = s.cloudBase[c];
    const int32_t at = index[k];
    float w = s.updraft[c];
    bool triggered = false;
    float cape = 0.0f, neutralBuoyancy = 0.0f;
    if (maxCape[at] > 0.0f && kinetic[k] >= minCin[at]) {
      const float ta = fractionA[k], td = fractionD[k];
      const Lanes v00 = node(at), v10 = node(at + 1), v01 = node(at + stride), v11 = node(at + stride + 1);
      const Lanes lo = v00 + ta * (v10 - v00), hi = v01 + ta * (v11 - v01), v = lo + td * (hi - lo);
      cape = v[0];
      float cin = 0.5f * v[1] * v[1];
      neutralBuoyancy = v[2];
      if (cape > 0.0f && !allFree[at]) {
        const ParcelProperties parcel = table.lookup(ParcelTable::Position{size_t(at), ta, td});
        cape = parcel.cape_J_kg;
        cin = parcel.cin_J_kg;
        neutralBuoyancy = parcel.neutralBuoyancyLevel_m;
      }
      triggered = cape > 0.0f && kinetic[k] >= cin;
    }
    if (!triggered && w == 0.0f) return;
    const float target = triggered ? std::min(0.5f * std::sqrt(2.0f * cape), 60.0f) : 0.0f;
    w += (target - w) * relax;
    if (w < 0.01f) w = 0.0f;  // a dead updraft is zero, not an endless exponential tail
    s.updraft[c] = w;
    updraftSum += w;
    if (!triggered || w < 0.05f) return;

    // Cloud top: grows at w toward the LNB plus overshoot; collapses toward it if above.
    const float topTarget = std::min(std::max(neutralBuoyancy, lcl) + w / kBuoyancyFrequency, maxTop);
    float top = std::max(s.cloudTop[c], lcl);
    top = top < topTarget ? std::min(topTarget, top + w * dt) : topTarget + (top - topTarget) * (1.0f - relax);
    s.cloudTop[c] = top;

    // Condensation into the core.
    const float lclTemperature = surfaceT - float(kDryAdiabaticLapseRate) * lcl;
    const float topTemperature = lclTemperature - kMeanMoistLapse * (top - lcl);
    const float topPressure = p0 * expFast(top * invScaleHeight);
    const float remaining = rhoH * saturationMixingRatioFast(topTemperature, topPressure);
    const float exchange = oneMinusExpFast(exchangePerUpdraft * w);
    const float dq = std::max(0.0f, vapour - remaining) * exchange;
    const float cloud = s.cloudWater[c];
    // The cloud gains dq, the cell's vapour loses its own share; what the stored floats gained and lost
    // differs by the catchment's share (and round-off), booked exactly in double.
    const float newCloud = cloud + dq, newVapour = std::max(0.0f, vapour - ownShare * dq);
    drawn += (double(newCloud) - double(cloud)) - (double(vapour) - double(newVapour));
    s.cloudWater[c] = newCloud;
    s.vapour[c] = newVapour;
    const float conv = s.convectiveFraction[c];
    s.convectiveFraction[c] = cloud + dq > 0.0f ? (conv * cloud + dq) / (cloud + dq) : 1.0f;
    // The exchanged air is replaced by the surroundings': a warm anomaly relaxes toward them.
    if (anomaly > environment) s.temperature[c] = environment + (anomaly - environment) * (1.0f - exchange);
  });
  return {double(kCoreFraction) * updraftSum / double(n), drawn};
}

}  // namespace firmament::weather
