#pragma once
// Inference of column roles from names and units, with overrides.
// Name aliases cover MTS (Running Time, Axial Force, Axial Displacement, Axial Strain, Strain 1,
// Axial Ext), MTS 793 German labels (Laufzeit, Kraft, Weg, Dehnung), Instron Bluehill (Time,
// Extension = crosshead, Load; Bluehill Universal Displacement, Force) and plain names.
// Command/setpoint channels (Sollwert, Command) are never chosen.

#include <map>
#include <string>
#include <vector>

#include "lab_data/load_frame_test.hpp"

namespace gradem::lab {

struct RoleAssignment {
    std::map<ChannelRole, std::size_t> column;  ///< role -> index into RawTable::columns
    std::vector<std::string> notes;             ///< ambiguities resolved
};

/// Assigns roles; throws InputError when an override names a column the file does not have.
RoleAssignment assign_roles(const RawTable& table, const ChannelOverrides& overrides);

/// Lower case, '_' '-' '.' ':' as spaces, single spaces, "ch 1 "/"channel 1 " prefix removed.
std::string normalise_channel_name(std::string_view name);

}  // namespace gradem::lab
