// Built where pugixml (Debian libpugixml-dev) is not installed: geometry.xml is refused by name.
#include "cli/openmc_geometry.hpp"

namespace linequad::cli {

bool openmc_geometry_available() {
    return false;
}

bool parse_openmc_geometry(std::string_view, ModelFile* out, std::string* why) {
    *out = ModelFile{};
    *why = "this linequad was built without pugixml (Debian libpugixml-dev: bash "
           "scripts/install-deps.sh, then build again), so it cannot read OpenMC's geometry.xml";
    return false;
}

} // namespace linequad::cli
