// GL/DX green-channel convention of a tangent-space normal map, decided from its content.
//
// Conventions (rows of an image go DOWN; x goes right):
//   GL (+Y, green up):  n ∝ (−s·∂h/∂x, +s·∂h/∂row, 1)
//   DX (−Y, green down): n ∝ (−s·∂h/∂x, −s·∂h/∂row, 1)
// with h the height, s > 0 the bump strength, and n decoded from 8/16-bit values as n = 2c − 1.
// So the slopes p = −n_x/n_z = s·∂h/∂x and q = n_y/n_z = ±s·∂h/∂row (+ for GL).
//
// Two tests, both run on a small pyramid (blocks of 1, 2, 4, 8 pixels: averaging slopes is a
// linear filter, so it keeps both tests valid while averaging out per-pixel noise):
//  - height test (when the set has a height/displacement map): the sign of the correlation of q
//    with ∂h/∂row. The red channel has no GL/DX ambiguity, so corr(p, ∂h/∂x) > 0 checks that the
//    pair belongs together; when it does not, the height evidence counts half. A map stored as
//    depth (white = deep: h' = −h) turns both correlations negative: their relative sign, which
//    inversion leaves alone, decides, and corr(p, ∂h/∂x) ≤ −kDepthMinCorrelation says the map is
//    depth (NormalVerdict::height_is_depth).
//  - integrability (curl) test: a field of slopes that comes from a height is curl-free,
//    ∂p/∂row = ∂q_true/∂x. Under the right convention A = ∂p/∂row and B = ∂(n_y/n_z)/∂x agree
//    (GL: A = B, DX: A = −B); Σ(A∓B)² differ by 4ΣAB, so the sign of corr(A, B) decides. A
//    height that varies along one axis only (stripes, planks) has no mixed derivative: the test
//    then has no evidence, and says so (low confidence, verdict unknown).
// Confidence in [0, 1] maps the absolute correlations (docs/rules.md "Normal convention").
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "findings/findings.hpp"
#include "image/image.hpp"
#include "material/roles.hpp"

namespace mf::validate {

struct DetectorOptions {
    int levels = 4;                // pyramid levels: blocks of 1, 2, 4, 8 pixels
    long min_samples = 256;        // a level needs this many interior pixels to vote
    double min_confidence = 0.25;  // below this the verdict is `unknown`
    double min_nz = 0.1;           // n_z is clamped to at least this before dividing
    // Flat: the slopes p, q vary by at most this (standard deviation, in slope units) — a flat
    // or constant map, whose green convention changes nothing. 0.02 is ±2.5 codes of 8-bit noise;
    // the flattest vendor map measured (3dtextures.me Surface_Imperfection_001, 1K JPEG) has 0.081.
    double flat_max_slope_std = 0.02;
};

struct NormalVerdict {
    NormalConvention convention = NormalConvention::unknown;
    double confidence = 0.0;  // of the direction the evidence leans to, even if unknown
    NormalConvention leaning = NormalConvention::unknown;
    std::string method = "none";  // "height+curl", "curl", "none"
    bool flat = false;            // no relief: the convention does not matter (see DetectorOptions)
    // The height map is stored as depth (white = deep): its x gradient anticorrelates with the
    // normal's red slope. Ingest writes it white = high (plan: HEIGHT_STORED_AS_DEPTH).
    bool height_is_depth = false;
    // Its x gradient correlates with the red slope as a height's does (at least
    // kDepthMinCorrelation): stored white = high, whatever its name says.
    bool height_is_height = false;
    Figures figures;
};

// corr(p, ∂h/∂x) at or below minus this: the height map is depth. On the corpus
// (CorpusNormals.RealMapsPassOthersFailWithMargin) the matched height maps correlate in red at
// +0.457 to +0.999, but for Metal_Rusted_010's +0.149; a map read against a height it does not
// belong to stays within ±0.120. 0.3 is 2.5x the unrelated maps' and 1.5x under 0.457: a
// mismatched pair is never taken for depth (which would invert the height output), and a depth
// map as weakly tied as Metal_Rusted_010's is left as before (its evidence counts half).
inline constexpr double kDepthMinCorrelation = 0.3;

// One decoded row of a normal map: its unit-free components as three planes (the detector reads
// them four at a time).
struct NormalRow {
    std::vector<float> x, y, z;
};

// Decodes one row of a normal map into `out` (resized to `width`). `channels`: 2 (z rebuilt as
// sqrt(1 − x² − y²), as BC5/two-channel maps), ≥ 3 (RGB, extra channels ignored). `signed_values`:
// the file already stores −1…1 (some float maps); otherwise n = 2c − 1.
// `rebuild_z`: Z from X and Y (sqrt(1 - x² - y²)) whatever a third channel holds (a two-channel,
// BC5-style map whose blue is empty); with 2 channels it always is.
void decode_normal_row(const float* src, int channels, int width, bool signed_values, NormalRow& out,
                       bool rebuild_z = false);
// The same of a row held as 8-bit codes (unorm8_values; never signed): the floats' components bit for bit.
void decode_normal_row(const uint8_t* codes, int channels, int width, NormalRow& out, bool rebuild_z = false);

// Streaming detector: feed decoded rows top to bottom (and the height row of the same grid, or
// nullptr when there is no height map). Memory: a few rows per pyramid level.
class NormalConventionDetector {
public:
    NormalConventionDetector(int width, bool with_height, const DetectorOptions& opt = {});
    ~NormalConventionDetector();
    NormalConventionDetector(NormalConventionDetector&&) noexcept;
    NormalConventionDetector& operator=(NormalConventionDetector&&) noexcept;

    void add_row(const NormalRow& row, const float* height);
    NormalVerdict verdict() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Whole-image convenience (ingest: ≤ 4K maps). `height` may be null or of another size (it is
// sampled by nearest neighbour onto the normal's grid); its first channel is used.
NormalVerdict detect_normal_convention(const Image& normal, const Image* height = nullptr,
                                       const DetectorOptions& opt = {}, bool signed_values = false);

}  // namespace mf::validate
