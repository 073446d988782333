#include "core/util/byte_stream.h"

#include <stdexcept>

namespace rrf {

void ByteReader::fail() const {
    throw std::runtime_error(source_ + ": truncated transfer (" + std::to_string(bytes_.size()) + " bytes, read past byte " +
                             std::to_string(at_) + ")");
}

}  // namespace rrf
