// The largest image side, decided once: what ingest writes without OUTPUT_TOO_LARGE, what the
// decoder accepts (with kMaxPixels, its decompression-bomb guard), what a preview renders, and
// the largest bare number discovery takes for a resolution tag.
#pragma once

namespace mf {

// 16384 pixels: D3D12's 2D texture limit (D3D12_REQ_TEXTURE2D_U_OR_V_DIMENSION), what Unity,
// Unreal and Godot import, and the maxImageDimension2D of lavapipe and of every desktop GPU this
// project has run on (Vulkan itself guarantees only 4096).
inline constexpr int kMaxImageSide = 16384;

}  // namespace mf
