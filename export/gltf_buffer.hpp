#pragma once
// The one buffer of a .glb being built (glb_writer.cpp, deployment_glb.cpp): bytes appended as a
// buffer view. Needs tiny_gltf.h (Debian libtinygltf-dev), which only the export library sees.
#include <tiny_gltf.h>

#include <cstring>

namespace egg::exporter {

// Appends `size` bytes to buffer 0, 4-byte aligned (accessors align to their component size), as
// a new buffer view with the given target (0: none, as animation data must be); returns its index.
inline int appendBufferView(tinygltf::Model& gltf, const void* bytes, size_t size, int target) {
  auto& data = gltf.buffers[0].data;
  const size_t offset = (data.size() + 3) / 4 * 4;
  data.resize(offset + size);
  std::memcpy(data.data() + offset, bytes, size);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = offset;
  v.byteLength = size;
  v.target = target;
  gltf.bufferViews.push_back(v);
  return static_cast<int>(gltf.bufferViews.size()) - 1;
}

}  // namespace egg::exporter
