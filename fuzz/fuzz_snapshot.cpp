// libFuzzer harness for the snapshot readers (see fuzz/run.sh). FUZZ_FORMAT picks the reader
// the bytes go to directly (1: extended XYZ, 2: LAMMPS dump, 3: GSD); each frame the file
// indexes is read. A UserError is the correct answer to bad bytes; anything else (a crash, a
// sanitizer report, another exception, a huge allocation) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/gsd.h"
#include "io/lammps_dump.h"
#include "io/snapshot_file.h"
#include "io/xyz.h"
#include "sim/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::MappedFile file =
      gs::MappedFile::from_bytes("fuzz", std::string(reinterpret_cast<const char*>(data), size));
  try {
#if FUZZ_FORMAT == 1
    auto source = gs::open_xyz(std::move(file));
#elif FUZZ_FORMAT == 2
    auto source = gs::open_lammps_dump(std::move(file));
#else
    auto source = gs::open_gsd(std::move(file));
#endif
    const gs::SnapshotFile f(std::move(source), "fuzz", {});
    // A hostile index may claim many frames: the first few and the last are enough.
    const std::size_t n = f.frame_count();
    for (std::size_t k = 0; k < n && k < 4; ++k) f.read(k);
    if (n > 4) f.read(n - 1);
  } catch (const gs::UserError&) {
  }
  return 0;
}
