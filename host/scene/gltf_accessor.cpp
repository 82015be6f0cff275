// Validated reads of glTF accessors (glTF 2.0 sec. 3.6): every byte an accessor names is checked
// to lie inside its bufferView and buffer before anything is read, so a malformed file gives an
// error naming the accessor instead of reading out of bounds.
#include <algorithm>
#include <cstring>
#include <limits>
#include <type_traits>

#include "scene/gltf_parts.h"

namespace vkp::gltf {

namespace {

/// Most elements of one accessor (an accessor without a bufferView is all zeros: its count is
/// not bounded by the file's size).
constexpr std::size_t kMaxAccessorCount = std::size_t(1) << 28;

const char* componentName(int type) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "byte";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "unsigned byte";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "unsigned short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "unsigned int";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "float";
    default: return "unknown";
    }
}

const char* typeName(int components) {
    switch (components) {
    case 1: return "SCALAR";
    case 2: return "VEC2";
    case 3: return "VEC3";
    case 4: return "VEC4";
    default: return "?";
    }
}

/// One component read from p (little-endian as on every machine vkpath runs on), as Out. Floats:
/// normalized integers per glTF 2.0 sec. 3.11 ("Animations": the normalization equations).
template <class T, class Out>
Out convert(const std::uint8_t* p, bool normalized) {
    T v;
    std::memcpy(&v, p, sizeof v);
    if constexpr (std::is_floating_point_v<Out>) {
        if constexpr (std::is_integral_v<T>) {
            if (normalized) {
                const float x = float(v) / float(std::numeric_limits<T>::max());
                return std::is_signed_v<T> ? std::max(x, -1.0f) : x;
            }
        }
        return static_cast<Out>(v);
    } else {
        return static_cast<Out>(v);  // uints(): T is an unsigned integer type
    }
}

template <class Out, class F>
void dispatch(int componentType, F&& f) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: f(std::int8_t{}); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: f(std::uint8_t{}); break;
    case TINYGLTF_COMPONENT_TYPE_SHORT: f(std::int16_t{}); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: f(std::uint16_t{}); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: f(std::uint32_t{}); break;
    default: f(float{}); break;
    }
}

std::size_t sparseIndex(const std::uint8_t* p, int type, std::size_t i) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[i];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return convert<std::uint16_t, std::uint32_t>(p + 2 * i, false);
    default: return convert<std::uint32_t, std::uint32_t>(p + 4 * i, false);
    }
}

}  // namespace

int componentSize(int type) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;  // INT and DOUBLE are not glTF 2.0 accessor component types
    }
}


std::string Accessor::place() const { return "accessor " + std::to_string(index_) + " (" + use_ + ")"; }

void Accessor::fail(const std::string& message) const { gltf::fail(doc_->file, place(), message); }

Accessor::Accessor(const Document& doc, int index, std::string use, int components, std::initializer_list<int> allowed)
    : doc_(&doc), index_(index), use_(std::move(use)) {
    const tinygltf::Model& m = doc.model;
    if (index < 0 || std::size_t(index) >= m.accessors.size()) {
        fail("does not exist (the file has " + std::to_string(m.accessors.size()) + " accessors)");
    }
    const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
    componentType_ = a.componentType;
    const int size = componentSize(a.componentType);
    if (size == 0) fail("componentType " + std::to_string(a.componentType) + " is not a glTF 2.0 component type");
    switch (a.type) {
    case TINYGLTF_TYPE_SCALAR: components_ = 1; break;
    case TINYGLTF_TYPE_VEC2: components_ = 2; break;
    case TINYGLTF_TYPE_VEC3: components_ = 3; break;
    case TINYGLTF_TYPE_VEC4: components_ = 4; break;
    default: fail("type " + std::to_string(a.type) + " (a matrix or unknown type) cannot be used here");
    }
    if (components_ != components || std::find(allowed.begin(), allowed.end(), componentType_) == allowed.end()) {
        std::string list;
        for (int t : allowed) list += (list.empty() ? "" : ", ") + std::string(componentName(t));
        fail(std::string("is ") + typeName(components_) + " of " + componentName(componentType_) + ", expected " +
             typeName(components) + " of " + list);
    }
    count_ = a.count;
    normalized_ = a.normalized;
    if (count_ == 0) fail("count must be >= 1");
    if (count_ > kMaxAccessorCount) {
        fail("count " + std::to_string(count_) + " is larger than vkpath's limit of " + std::to_string(kMaxAccessorCount));
    }
    const std::size_t element = std::size_t(size) * std::size_t(components_);

    // The bytes [offset, offset + length) of bufferView v, checked against its buffer.
    auto view = [&](int v, const std::string& what) -> std::pair<const std::uint8_t*, std::size_t> {
        if (v < 0 || std::size_t(v) >= m.bufferViews.size()) {
            fail(what + " bufferView " + std::to_string(v) + " does not exist (the file has " +
                 std::to_string(m.bufferViews.size()) + ")");
        }
        const tinygltf::BufferView& bv = m.bufferViews[std::size_t(v)];
        if (bv.buffer < 0 || std::size_t(bv.buffer) >= m.buffers.size()) {
            fail("bufferView " + std::to_string(v) + " names buffer " + std::to_string(bv.buffer) + ", which does not exist");
        }
        const auto& data = m.buffers[std::size_t(bv.buffer)].data;
        if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset) {
            fail("bufferView " + std::to_string(v) + " (offset " + std::to_string(bv.byteOffset) + ", length " +
                 std::to_string(bv.byteLength) + ") is outside buffer " + std::to_string(bv.buffer) + " (" +
                 std::to_string(data.size()) + " bytes)");
        }
        return {data.data() + bv.byteOffset, bv.byteLength};
    };
    // n elements of elementBytes each, stride apart, from offset inside a view of length bytes.
    auto fits = [](std::size_t offset, std::size_t n, std::size_t stride, std::size_t elementBytes, std::size_t length) {
        if (offset > length) return false;
        return (n - 1) * stride + elementBytes <= length - offset;  // n <= 2^28, stride <= 252: no overflow
    };

    if (a.bufferView >= 0) {
        const auto [bytes, length] = view(a.bufferView, "its");
        const std::size_t declared = m.bufferViews[std::size_t(a.bufferView)].byteStride;
        if (declared != 0 && (declared < element || declared > 252)) {
            fail("bufferView " + std::to_string(a.bufferView) + " byteStride " + std::to_string(declared) +
                 " is not in [" + std::to_string(element) + ", 252] (the element is " + std::to_string(element) + " bytes)");
        }
        stride_ = declared != 0 ? declared : element;
        if (!fits(a.byteOffset, count_, stride_, element, length)) {
            fail(std::to_string(count_) + " elements of " + std::to_string(element) + " bytes, " + std::to_string(stride_) +
                 " apart, from offset " + std::to_string(a.byteOffset) + " do not fit bufferView " +
                 std::to_string(a.bufferView) + " (" + std::to_string(length) + " bytes)");
        }
        data_ = bytes + a.byteOffset;
    }

    if (a.sparse.isSparse) {
        const auto& s = a.sparse;
        if (s.count < 1 || std::size_t(s.count) > count_) {
            fail("sparse count " + std::to_string(s.count) + " is not in [1, " + std::to_string(count_) + "]");
        }
        sparseCount_ = std::size_t(s.count);
        sparseIndexType_ = s.indices.componentType;
        const int indexSize = componentSize(sparseIndexType_);
        if (sparseIndexType_ != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            sparseIndexType_ != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            sparseIndexType_ != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            fail("sparse indices componentType " + std::to_string(sparseIndexType_) + " is not an unsigned integer type");
        }
        const auto [ib, il] = view(s.indices.bufferView, "sparse indices");
        if (s.indices.byteOffset < 0 || !fits(std::size_t(s.indices.byteOffset), sparseCount_, std::size_t(indexSize),
                                              std::size_t(indexSize), il)) {
            fail("sparse indices (" + std::to_string(sparseCount_) + " from offset " + std::to_string(s.indices.byteOffset) +
                 ") do not fit bufferView " + std::to_string(s.indices.bufferView));
        }
        const auto [vb, vl] = view(s.values.bufferView, "sparse values");
        if (s.values.byteOffset < 0 || !fits(std::size_t(s.values.byteOffset), sparseCount_, element, element, vl)) {
            fail("sparse values (" + std::to_string(sparseCount_) + " from offset " + std::to_string(s.values.byteOffset) +
                 ") do not fit bufferView " + std::to_string(s.values.bufferView));
        }
        sparseIndices_ = ib + s.indices.byteOffset;
        sparseValues_ = vb + s.values.byteOffset;
        std::size_t previous = 0;
        for (std::size_t i = 0; i < sparseCount_; ++i) {
            const std::size_t k = sparseIndex(sparseIndices_, sparseIndexType_, i);
            if (k >= count_ || (i > 0 && k <= previous)) {
                fail("sparse index " + std::to_string(i) + " is " + std::to_string(k) +
                     (k >= count_ ? " (the accessor has " + std::to_string(count_) + " elements)"
                                  : " (indices must increase strictly)"));
            }
            previous = k;
        }
    }
}

template <class Out>
void Accessor::readDense(Out* out) const {
    const std::size_t n = std::size_t(components_);
    if (!data_) {
        std::fill(out, out + count_ * n, Out{});
        return;
    }
    dispatch<Out>(componentType_, [&](auto tag) {
        using T = decltype(tag);
        for (std::size_t i = 0; i < count_; ++i) {
            const std::uint8_t* p = data_ + i * stride_;
            for (std::size_t c = 0; c < n; ++c) out[i * n + c] = convert<T, Out>(p + c * sizeof(T), normalized_);
        }
    });
}

template <class Out>
void Accessor::applySparse(Out* out) const {
    const std::size_t n = std::size_t(components_);
    dispatch<Out>(componentType_, [&](auto tag) {
        using T = decltype(tag);
        for (std::size_t i = 0; i < sparseCount_; ++i) {
            const std::size_t k = sparseIndex(sparseIndices_, sparseIndexType_, i);
            const std::uint8_t* p = sparseValues_ + i * n * sizeof(T);
            for (std::size_t c = 0; c < n; ++c) out[k * n + c] = convert<T, Out>(p + c * sizeof(T), normalized_);
        }
    });
}

std::vector<float> Accessor::floats() const {
    std::vector<float> out(count_ * std::size_t(components_));
    readDense(out.data());
    if (sparseCount_) applySparse(out.data());
    return out;
}

std::vector<std::uint32_t> Accessor::uints() const {
    if (components_ != 1 || componentType_ == TINYGLTF_COMPONENT_TYPE_FLOAT || componentType_ == TINYGLTF_COMPONENT_TYPE_BYTE ||
        componentType_ == TINYGLTF_COMPONENT_TYPE_SHORT) {
        fail("is not a SCALAR of unsigned integers");  // a caller's mistake: constructed with other types
    }
    std::vector<std::uint32_t> out(count_);
    readDense(out.data());
    if (sparseCount_) applySparse(out.data());
    return out;
}

}  // namespace vkp::gltf
