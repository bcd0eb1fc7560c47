// What a relume.Compressed holds: the compressed field, how save() stores it (precisions and the
// parameters recorded in the header), and the relighters made for it, kept so that relighting
// again on the same device uploads the field only once.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <relume/compressed_field.hpp>
#include <relume/container.hpp>
#include <relume/relight.hpp>
#include <string>

namespace relume::python {

struct CompressedObject {
  CompressedField field;
  ContainerOptions storage;
  // Guards the relighters: relighting runs with the GIL released, maybe on several threads.
  std::mutex relighting;
  std::map<std::string, std::unique_ptr<Relighter>> opencl;  // by device selector
  std::unique_ptr<Relighter> reference;                      // the CPU reference
};

}  // namespace relume::python
