#include "particles/storage/CopyImage.hpp"

#include "core/Error.hpp"

#include <string>

namespace regolith::particles {

namespace {

CopyImage checked(std::array<int, 3> const& k) {
    CopyImage out{};
    for (int a = 0; a < 3; ++a) {
        if (k[a] < -kMaxImage || k[a] > kMaxImage)
            throw core::Error("periodic image " + std::to_string(k[a]) + " on axis " +
                              std::to_string(a) + " is beyond +-" + std::to_string(kMaxImage) +
                              ": a grain reaches several domain periods away");
        out[a] = static_cast<std::int8_t>(k[a]);
    }
    return out;
}

} // namespace

CopyImage addImages(CopyImage const& a, CopyImage const& b) {
    return checked({a[0] + b[0], a[1] + b[1], a[2] + b[2]});
}

CopyImage subtractImages(CopyImage const& a, CopyImage const& b) {
    return checked({a[0] - b[0], a[1] - b[1], a[2] - b[2]});
}

CopyImage imageThroughLink(CopyImage const& from, std::array<int, 3> const& linkImage) {
    // x in the sender's frame is x + shift = x - linkImage * extent in the neighbour's frame.
    return checked({from[0] - linkImage[0], from[1] - linkImage[1], from[2] - linkImage[2]});
}

} // namespace regolith::particles
