// MaterialX documents as sidecars (discovery.hpp "Sidecars"): which texture feeds which input of
// the surface shader. Parsed with libxml2 (no network, no entity substitution, no DTD loading):
// a document is read as data, never trusted for paths (every file resolves inside the set).
#include <libxml/parser.h>
#include <libxml/tree.h>

#include <array>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "material/sidecar_util.hpp"

namespace mf::sidecar {
namespace {

// Shader inputs with a role, across the surface shaders of MaterialX 1.38/1.39's standard
// libraries (their names do not collide): standard_surface, gltf_pbr, open_pbr_surface and
// UsdPreviewSurface; "displacement" is also the displacement shader's input.
constexpr std::array<std::pair<std::string_view, Role>, 17> kShaderInputs{{
    {"base_color", Role::albedo},         // standard_surface, gltf_pbr, open_pbr_surface
    {"diffuseColor", Role::albedo},       // UsdPreviewSurface
    {"metalness", Role::metalness},       // standard_surface
    {"metallic", Role::metalness},        // gltf_pbr, UsdPreviewSurface
    {"base_metalness", Role::metalness},  // open_pbr_surface
    {"specular_roughness", Role::roughness},
    {"roughness", Role::roughness},
    {"normal", Role::normal},
    {"geometry_normal", Role::normal},
    {"emission_color", Role::emissive},
    {"emissive", Role::emissive},
    {"emissiveColor", Role::emissive},
    {"opacity", Role::opacity},
    {"alpha", Role::opacity},
    {"geometry_opacity", Role::opacity},
    {"occlusion", Role::occlusion},
    {"displacement", Role::height},
    // Coat inputs (ambientCG's coat_normal, coat_roughness) reuse the base maps: no role of their own.
}};

std::optional<Role> input_role(std::string_view name) {
    for (const auto& [input, role] : kShaderInputs)
        if (input == name) return role;
    return std::nullopt;
}

std::string attr(const xmlNode* n, const char* name) {
    xmlChar* v = xmlGetProp(n, reinterpret_cast<const xmlChar*>(name));
    if (!v) return {};
    std::string s(reinterpret_cast<const char*>(v));
    xmlFree(v);
    return s;
}

bool named(const xmlNode* n, std::string_view name) {
    return n->type == XML_ELEMENT_NODE && name == reinterpret_cast<const char*>(n->name);
}

struct Input {
    std::string name, type, value, nodename, nodegraph, output, fileprefix;
};

struct Node {
    std::string category, type, fileprefix;
    std::vector<Input> inputs;
    const Input* input(std::string_view name) const {
        for (const auto& i : inputs)
            if (i.name == name) return &i;
        return nullptr;
    }
};

// A scope of named nodes: the document, or one nodegraph (with its outputs).
struct Scope {
    std::string fileprefix;
    std::map<std::string, Node> nodes;
    std::map<std::string, std::string> outputs;  // output name -> node name
};

struct Document {
    Scope top;
    std::map<std::string, Scope> graphs;
};

void read_scope(const xmlNode* parent, Scope& scope, Document* doc) {
    for (const xmlNode* n = parent->children; n; n = n->next) {
        if (n->type != XML_ELEMENT_NODE) continue;
        const std::string category = reinterpret_cast<const char*>(n->name);
        const std::string name = attr(n, "name");
        if (category == "nodegraph" && doc) {
            Scope& g = doc->graphs[name];
            g.fileprefix = attr(n, "fileprefix");
            if (g.fileprefix.empty()) g.fileprefix = scope.fileprefix;
            read_scope(n, g, nullptr);  // nodegraphs do not nest
            continue;
        }
        if (category == "output") {
            scope.outputs[name] = attr(n, "nodename");
            continue;
        }
        if (name.empty() || category == "look" || category == "materialassign") continue;
        Node node{category, attr(n, "type"), attr(n, "fileprefix"), {}};
        if (node.fileprefix.empty()) node.fileprefix = scope.fileprefix;
        for (const xmlNode* i = n->children; i; i = i->next)
            if (named(i, "input"))
                node.inputs.push_back({attr(i, "name"), attr(i, "type"), attr(i, "value"), attr(i, "nodename"),
                                       attr(i, "nodegraph"), attr(i, "output"), attr(i, "fileprefix")});
        scope.nodes.emplace(name, std::move(node));
    }
}

struct Reached {
    std::string file;  // the image node's file with its fileprefix, as written
    bool via_normalmap = false;
};

// The image an input is connected to, through at most kMaxHops nodes (a cycle ends there).
constexpr int kMaxHops = 16;
std::optional<Reached> follow(const Document& doc, const Scope& scope, const Input& in, int hops, bool normalmap) {
    if (hops > kMaxHops) return std::nullopt;
    const Scope* where = &scope;
    std::string node_name = in.nodename;
    if (node_name.empty() && !in.nodegraph.empty()) {
        const auto g = doc.graphs.find(in.nodegraph);
        if (g == doc.graphs.end()) return std::nullopt;
        where = &g->second;
        if (!in.output.empty()) {
            const auto o = where->outputs.find(in.output);
            if (o == where->outputs.end()) return std::nullopt;
            node_name = o->second;
        } else if (where->outputs.size() == 1) {
            node_name = where->outputs.begin()->second;
        }
    }
    if (node_name.empty()) return std::nullopt;
    const auto it = where->nodes.find(node_name);
    if (it == where->nodes.end()) return std::nullopt;
    const Node& node = it->second;
    if (const Input* file = node.input("file"); file && file->type == "filename") {
        if (file->value.empty()) return std::nullopt;
        const std::string& prefix = file->fileprefix.empty() ? node.fileprefix : file->fileprefix;
        return Reached{prefix + file->value, normalmap};
    }
    const bool is_normalmap = node.category == "normalmap";
    // Pass-through nodes (normalmap, extract, swizzle, convert, multiply, ...): their first
    // connected input among the usual names leads on.
    for (const char* next : {"in", "in1", "input", "fg", "bg"})
        if (const Input* i = node.input(next); i && (!i->nodename.empty() || !i->nodegraph.empty()))
            return follow(doc, *where, *i, hops + 1, normalmap || is_normalmap);
    return std::nullopt;
}

struct XmlDocDeleter {
    void operator()(xmlDoc* d) const { xmlFreeDoc(d); }
};

}  // namespace

void read_materialx(std::string_view content, std::string_view source, SidecarRoles& out) {
    // libxml2 is thread-safe once initialised, which must happen before threads parse.
    static std::once_flag init;
    std::call_once(init, [] { xmlInitParser(); });
    if (content.size() > static_cast<size_t>(std::numeric_limits<int>::max())) {
        out.error = "too large";
        return;
    }
    const std::unique_ptr<xmlDoc, XmlDocDeleter> xml(xmlReadMemory(content.data(), static_cast<int>(content.size()),
                                                                   nullptr, nullptr,
                                                                   XML_PARSE_NONET | XML_PARSE_NOERROR |
                                                                       XML_PARSE_NOWARNING | XML_PARSE_NOCDATA));
    const xmlNode* root = xml ? xmlDocGetRootElement(xml.get()) : nullptr;
    if (!root || !named(root, "materialx")) {
        out.error = xml ? "not a MaterialX document (no <materialx> root)" : "not well-formed XML";
        return;
    }
    out.kind = SidecarKind::materialx;
    Document doc;
    doc.top.fileprefix = attr(root, "fileprefix");
    read_scope(root, doc.top, &doc);
    // Every role each file is reached for, in document order.
    std::map<std::string, std::set<Role>> roles_of;
    std::vector<std::pair<std::string, NameMatch>> found;
    for (const auto& [name, node] : doc.top.nodes) {
        if (node.type != "surfaceshader" && node.type != "displacementshader") continue;
        for (const Input& in : node.inputs) {
            const auto role = input_role(in.name);
            if (!role) continue;
            const auto reached = follow(doc, doc.top, in, 0, false);
            if (!reached) continue;
            const auto file = resolve(source, reached->file, false);
            if (!file) continue;
            NameMatch m;
            m.role = *role;
            m.rule = "mtlx:" + node.category + "." + in.name;
            m.sidecar = std::string(source);
            if (*role == Role::normal && reached->via_normalmap) m.normal = NormalConvention::gl;
            roles_of[*file].insert(*role);
            found.emplace_back(*file, std::move(m));
        }
    }
    for (auto& [file, m] : found)
        if (roles_of[file].size() == 1) add_map(out, file, std::move(m));
}

}  // namespace mf::sidecar
