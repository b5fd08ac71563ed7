// Plain CSV: a names row with units in the names ("Load (kN)", "load_kN"), optional
// "# key: value" comment lines above it. The last row of GRADEM_EXPORT_FORMATS: any file the
// other formats do not recognise is read as this.
#include "lab_data/export_readers.hpp"
#include "lab_data/formats/export_format_parts.hpp"

namespace gradem::lab {
namespace {

bool detect(const Lines&, const Dialect&) { return true; }

void read(RawTable& t, const Lines& lines) { formats::read_generic(t, lines); }

}  // namespace

extern const ExportFormatSpec plain_csv_format = {detect, read};

}  // namespace gradem::lab
