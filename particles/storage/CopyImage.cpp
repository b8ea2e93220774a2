#include "particles/storage/CopyImage.hpp"

#include "core/Error.hpp"

#include <string>

namespace regolith::particles::copy_image_detail {

void throwBeyondMaxImage(std::array<int, 3> const& k) {
    for (int a = 0; a < 3; ++a)
        if (k[a] < -kMaxImage || k[a] > kMaxImage)
            throw core::Error("periodic image " + std::to_string(k[a]) + " on axis " +
                              std::to_string(a) + " is beyond +-" + std::to_string(kMaxImage) +
                              ": a grain reaches several domain periods away");
    throw core::Error("throwBeyondMaxImage: no axis of the image is beyond the limit");
}

} // namespace regolith::particles::copy_image_detail
