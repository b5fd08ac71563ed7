#pragma once
// The messages between rank 0 and the worker ranks of an MPI calibration, as byte strings
// (no MPI here: the encoding is tested without it). Every message starts with a header
//   u32 magic "GRDM" | u32 protocol version | u32 byte-order mark 0x01020304 | u8 kind
// and then its fields in order: integers and doubles as their native 8 bytes (a double's
// exact bits: a result is bitwise the worker's), strings and vectors as a u64 count and the
// items. A header of another protocol version or byte order is a WireError naming both.
//
//   hello     worker -> 0  code version, host, pid, OpenMP threads, model fingerprint, error
//   prepare   0 -> worker  packing seeds to load (rank 0 made them; shared cache folder)
//   prepared  worker -> 0  seconds, error ("" = ready)
//   run       0 -> worker  job id, code version, model fingerprint hash, timeout [s],
//                          sand, packing seed, material (every field of exp::MaterialParams)
//   result    worker -> 0  job id, RunOutcome (status, reason, outputs, counts, wall time,
//                          thinned curve)
//   stop      0 -> worker  reason ("" = done; otherwise why rank 0 gives up)
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "calibrate/cube_model.hpp"
#include "common/named_enum.hpp"

namespace gradem::cal::wire {

inline constexpr std::uint32_t kProtocolVersion = 7;  // 7: the flat joint's unbonded_stiffness_ratio; 6: a bond law's fields written from its parameter rows

enum class Kind : std::uint8_t { hello = 1, prepare = 2, prepared = 3, run = 4, result = 5, stop = 6 };
constexpr EnumNameTable<Kind, 6> enum_name_table(Kind) {
    return {{{Kind::hello, "hello"},
             {Kind::prepare, "prepare"},
             {Kind::prepared, "prepared"},
             {Kind::run, "run"},
             {Kind::result, "result"},
             {Kind::stop, "stop"}}};
}

class WireError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct Hello {
    std::string code_version, host, model_fingerprint;
    std::int64_t pid = 0, threads = 1;
    std::string error;  ///< "" if the rank loaded the problem and model, else why not
};
struct Prepare {
    PackingSeeds seeds;
};
struct Prepared {
    double seconds = 0.0;
    std::string error;
};
struct Run {
    std::uint64_t job = 0;
    std::string code_version, model_hash;
    double timeout_s = 0.0;
    RunRequest request;
};
struct Result {
    std::uint64_t job = 0;
    RunOutcome outcome;
};
struct Stop {
    std::string reason;
};

std::string encode(const Hello& m);
std::string encode(const Prepare& m);
std::string encode(const Prepared& m);
std::string encode(const Run& m);
std::string encode(const Result& m);
std::string encode(const Stop& m);

/// The kind of a message; WireError if its header is not this protocol's.
Kind kind_of(const std::string& bytes);

Hello decode_hello(const std::string& bytes);
Prepare decode_prepare(const std::string& bytes);
Prepared decode_prepared(const std::string& bytes);
Run decode_run(const std::string& bytes);
Result decode_result(const std::string& bytes);
Stop decode_stop(const std::string& bytes);

}  // namespace gradem::cal::wire
