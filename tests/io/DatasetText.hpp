#pragma once
/// Tests' look into a checkpoint file: a dataset's string attribute, read with HDF5 directly.
#include <hdf5.h>

#include <cstring>
#include <string>

namespace regolith::test {

/// The string attribute `name` of dataset `set` in `path` ("" if absent).
inline std::string datasetText(std::string const& path, char const* set, char const* name) {
    hid_t const file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    hid_t const data = H5Dopen2(file, set, H5P_DEFAULT);
    std::string text;
    if (H5Aexists(data, name) > 0) {
        hid_t const attr = H5Aopen(data, name, H5P_DEFAULT);
        hid_t const type = H5Aget_type(attr);
        text.resize(H5Tget_size(type));
        H5Aread(attr, type, text.data());
        text.resize(std::strlen(text.c_str()));
        H5Tclose(type);
        H5Aclose(attr);
    }
    H5Dclose(data);
    H5Fclose(file);
    return text;
}

} // namespace regolith::test
