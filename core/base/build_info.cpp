#include "core/base/build_info.hpp"

#include "sonarsim_build_info.hpp" // generated in the build tree

namespace sonarsim {

const char* program_version() {
    return SONARSIM_VERSION;
}

const char* program_commit() {
    return SONARSIM_COMMIT;
}

} // namespace sonarsim
