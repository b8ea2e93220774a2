#pragma once
/// Errors raised by Regolith. The app entry point (core/app/RunApp.hpp) turns them into one
/// clear message and a non-zero exit code.
#include <stdexcept>
#include <string>

namespace regolith::core {

/// An error seen by one rank only (a corrupt message, a failed local check). The entry point
/// aborts the whole job on it so no other rank waits forever in a collective.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// An error in the input (scene file, option, initial state) that every rank detects in the
/// same way, because every rank reads the same input. The entry point lets every rank exit
/// cleanly with a non-zero code, rank 0 printing the message once.
class InputError : public Error {
public:
    using Error::Error;
};

/// An error in the input that one rank finds alone, inside a collective step where the others
/// cannot be told (NNS meeting a grain that the step carried beyond its reach, mid-sync). The
/// entry point prints it as an input error, naming the rank, and ends the job with the input
/// error's exit code (MPI_Abort: the other ranks may be waiting for this one).
class RankInputError : public Error {
public:
    using Error::Error;
};

/// A message buffer that is shorter than what is read from it, or corrupt.
class BufferError : public Error {
public:
    using Error::Error;
};

} // namespace regolith::core
