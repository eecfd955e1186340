// glTF accessors read with every offset, stride, count and index checked against the buffers,
// sparse ones made dense first.
#include "scene/gltf_internal.h"

#include <algorithm>
#include <cstring>

namespace ssgi {
namespace {

template <typename T> T load(const uint8_t* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T)); // glTF data need not be aligned for T
    return value;
}

[[noreturn]] void fail(const std::string& file, const std::string& problem) {
    throw InputError(file + ": " + problem);
}

std::string typeName(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
        return "VEC2";
    case TINYGLTF_TYPE_VEC3:
        return "VEC3";
    case TINYGLTF_TYPE_VEC4:
        return "VEC4";
    default:
        return "type " + std::to_string(type);
    }
}

// `count` elements of `elementSize` bytes from `byteOffset` into buffer view `index`, `stride`
// apart (0: as the view's byteStride says, else tightly packed): the first byte, after checking
// that the last element ends inside the view and the view inside its buffer. `what` names the
// data in messages.
const uint8_t* viewBytes(const tinygltf::Model& model, int index, size_t byteOffset, size_t count,
                         size_t elementSize, size_t& stride, const std::string& file,
                         const std::string& what) {
    if (index < 0 || size_t(index) >= model.bufferViews.size())
        fail(file, what + ": buffer view " + std::to_string(index) + " does not exist");
    const tinygltf::BufferView& bufferView = model.bufferViews[size_t(index)];
    if (bufferView.buffer < 0 || size_t(bufferView.buffer) >= model.buffers.size())
        fail(file, what + ": buffer " + std::to_string(bufferView.buffer) + " does not exist");
    const std::vector<unsigned char>& buffer = model.buffers[size_t(bufferView.buffer)].data;
    if (bufferView.byteOffset > buffer.size() ||
        bufferView.byteLength > buffer.size() - bufferView.byteOffset)
        fail(file, what + ": buffer view " + std::to_string(index) +
                       " runs past the end of its buffer (truncated file?)");
    if (stride == 0) stride = bufferView.byteStride ? bufferView.byteStride : elementSize;
    if (stride < elementSize)
        fail(file,
             what + ": byteStride " + std::to_string(stride) + " is smaller than one element");
    if (count > 0) {
        const bool fits = byteOffset <= bufferView.byteLength &&
                          elementSize <= bufferView.byteLength - byteOffset &&
                          count - 1 <= (bufferView.byteLength - byteOffset - elementSize) / stride;
        if (!fits)
            fail(file, what + ": " + std::to_string(count) +
                           " elements run past the end of buffer view " + std::to_string(index));
    }
    return buffer.data() + bufferView.byteOffset + byteOffset;
}

// A sparse accessor's elements made dense (glTF 2.0 section 3.6.2.3): its base (the buffer view,
// or zeros without one) with `count` elements replaced by the values its indices name.
std::shared_ptr<std::vector<uint8_t>> densify(const tinygltf::Model& model,
                                              const tinygltf::Accessor& accessor,
                                              const AccessorView& base, size_t elementSize,
                                              const std::string& file, const std::string& what) {
    const auto& sparse = accessor.sparse;
    const std::string where = what + ": sparse accessor";
    if (sparse.count < 1 || size_t(sparse.count) > base.count)
        fail(file, where + " replaces " + std::to_string(sparse.count) + " of " +
                       std::to_string(base.count) + " elements; 1 to " +
                       std::to_string(base.count) + " expected");
    if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
        fail(file, where + ": negative byteOffset");
    const int indexType = sparse.indices.componentType;
    if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(file, where + ": index component type " + std::to_string(indexType) +
                       " is not an unsigned integer type");
    const size_t count = size_t(sparse.count);
    const size_t indexSize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(indexType)));
    // Sparse indices and values are tightly packed, whatever their views' byteStride says.
    size_t indexStride = indexSize, valueStride = elementSize;
    const uint8_t* indices =
        viewBytes(model, sparse.indices.bufferView, size_t(sparse.indices.byteOffset), count,
                  indexSize, indexStride, file, where + " indices");
    const uint8_t* values =
        viewBytes(model, sparse.values.bufferView, size_t(sparse.values.byteOffset), count,
                  elementSize, valueStride, file, where + " values");

    auto dense = std::make_shared<std::vector<uint8_t>>(base.count * elementSize, uint8_t(0));
    // Each element is replaced once at most: with an index twice, which value holds would be
    // the reader's choice (the later one won, without a word).
    std::vector<uint32_t> entryOf(base.count, UINT32_MAX);
    if (base.data)
        for (size_t i = 0; i < base.count; ++i)
            std::memcpy(dense->data() + i * elementSize, base.data + i * base.stride, elementSize);
    for (size_t i = 0; i < count; ++i) {
        const uint8_t* p = indices + i * indexSize;
        const uint32_t target = indexSize == 1   ? *p
                                : indexSize == 2 ? load<uint16_t>(p)
                                                 : load<uint32_t>(p);
        if (target >= base.count)
            fail(file, where + ": index " + std::to_string(target) + " (entry " +
                           std::to_string(i) + ") is out of range for " +
                           std::to_string(base.count) + " elements");
        if (entryOf[target] != UINT32_MAX)
            fail(file, where + ": index " + std::to_string(target) + " appears twice (entries " +
                           std::to_string(entryOf[target]) + " and " + std::to_string(i) +
                           "); each element may be replaced once");
        entryOf[target] = uint32_t(i);
        std::memcpy(dense->data() + size_t(target) * elementSize, values + i * elementSize,
                    elementSize);
    }
    return dense;
}

} // namespace

float AccessorView::component(size_t element, int c) const {
    if (!data) return 0.0f;
    const uint8_t* p = data + element * stride + size_t(c) * size_t(componentSize);
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return normalized ? *p / 255.0f : *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        const float v = load<uint16_t>(p);
        return normalized ? v / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const float v = load<int8_t>(p);
        return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        const float v = load<int16_t>(p);
        return normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    default:
        return float(load<uint32_t>(p));
    }
}

uint32_t AccessorView::index(size_t element) const {
    if (!data) return 0;
    const uint8_t* p = data + element * stride;
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return load<uint16_t>(p);
    default:
        return load<uint32_t>(p);
    }
}

AccessorView viewAccessor(const tinygltf::Model& model, int index, int type,
                          std::initializer_list<int> allowedComponents, const std::string& file,
                          const std::string& what) {
    if (index < 0 || size_t(index) >= model.accessors.size())
        fail(file, what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& accessor = model.accessors[size_t(index)];
    const int code = accessor.normalized ? -accessor.componentType : accessor.componentType;
    if (std::find(allowedComponents.begin(), allowedComponents.end(), code) ==
        allowedComponents.end())
        fail(file, what + ": component type " + std::to_string(accessor.componentType) +
                       (accessor.normalized ? " (normalized)" : "") + " is not allowed here");
    if (accessor.type != type)
        fail(file,
             what + ": accessor is " + typeName(accessor.type) + ", expected " + typeName(type));

    AccessorView view;
    view.count = accessor.count;
    view.componentType = accessor.componentType;
    view.componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
    view.normalized = accessor.normalized;
    const size_t elementSize =
        size_t(view.componentSize) * size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
    if (accessor.bufferView < 0) {
        // Without a buffer view the elements are zeros (a sparse accessor replaces some): their
        // number is bounded by no data, so it is bounded by the data the file holds, or a small
        // file could ask for gigabytes.
        size_t held = 0;
        for (const tinygltf::Buffer& buffer : model.buffers)
            held += buffer.data.size();
        if (view.count > held)
            fail(file, what + ": accessor " + std::to_string(index) + " declares " +
                           std::to_string(view.count) +
                           " elements without a buffer view, more than the " +
                           std::to_string(held) + " bytes of data the file holds");
    } else {
        view.data = viewBytes(model, accessor.bufferView, accessor.byteOffset, view.count,
                              elementSize, view.stride, file, what);
        // The specification requires both; read anyway, the bytes would be other numbers (a
        // shifted float is a tiny or huge one) and the error would be found far from its cause.
        const size_t offset =
            model.bufferViews[size_t(accessor.bufferView)].byteOffset + accessor.byteOffset;
        if (offset % size_t(view.componentSize) != 0 ||
            view.stride % size_t(view.componentSize) != 0)
            fail(file, what + ": accessor " + std::to_string(index) + " starts at byte " +
                           std::to_string(offset) + " of its buffer with a stride of " +
                           std::to_string(view.stride) + ", not both multiples of its " +
                           std::to_string(view.componentSize) +
                           "-byte components (unaligned; the glTF specification requires them)");
    }
    if (accessor.sparse.isSparse) {
        view.dense = densify(model, accessor, view, elementSize, file, what);
        view.data = view.dense->data();
        view.stride = elementSize;
    }
    return view;
}

} // namespace ssgi
