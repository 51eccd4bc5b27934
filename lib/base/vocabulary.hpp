// The preset vocabulary, typed once when a preset is loaded (parse_preset): the file format, mip
// filter, encoder effort, KTX2 supercompression and material file. lib/texture and lib/image
// switch on these enums; word() is their spelling in presets (and in manifests), from_word()
// reads it back, word_list() lists it for messages. In lib/base (header-only, standard library
// only) because lib/image, below lib/preset, names the file formats.
#pragma once
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace mf {

enum class FileFormat { png, exr, tif, tga, dds, ktx2 };  // word(): also the files' extension
enum class MipFilter { box, kaiser };
enum class Effort { fast, normal, thorough };
enum class Supercompression { none, zstd };
enum class MaterialFileKind { none, gltf, godot, unity_hdrp, unity_urp, unreal, d3d11 };

// Each enum's words, in its enumerators' order.
template <class E>
struct Vocabulary;
template <>
struct Vocabulary<FileFormat> {
    static constexpr std::array<std::string_view, 6> words{"png", "exr", "tif", "tga", "dds", "ktx2"};
};
template <>
struct Vocabulary<MipFilter> {
    static constexpr std::array<std::string_view, 2> words{"box", "kaiser"};
};
template <>
struct Vocabulary<Effort> {
    static constexpr std::array<std::string_view, 3> words{"fast", "normal", "thorough"};
};
template <>
struct Vocabulary<Supercompression> {
    static constexpr std::array<std::string_view, 2> words{"none", "zstd"};
};
template <>
struct Vocabulary<MaterialFileKind> {
    static constexpr std::array<std::string_view, 7> words{"none",      "gltf",   "godot", "unity-hdrp",
                                                           "unity-urp", "unreal", "d3d11"};
};

template <class E>
constexpr std::string_view word(E e) {
    return Vocabulary<E>::words[static_cast<size_t>(e)];
}

template <class E>
constexpr std::optional<E> from_word(std::string_view w) {
    for (size_t i = 0; i < Vocabulary<E>::words.size(); ++i)
        if (Vocabulary<E>::words[i] == w) return static_cast<E>(i);
    return std::nullopt;
}

// "a, b or c".
template <class E>
std::string word_list() {
    const auto& w = Vocabulary<E>::words;
    std::string s;
    for (size_t i = 0; i < w.size(); ++i) s.append(i == 0 ? "" : i + 1 == w.size() ? " or " : ", ").append(w[i]);
    return s;
}

// dds and ktx2: outputs carry mip levels of GPU blocks (lib/texture).
constexpr bool is_block_container(FileFormat f) { return f == FileFormat::dds || f == FileFormat::ktx2; }

}  // namespace mf
