// legwork.walkcycle: bound once the walkcycle runtime is on the per-frame contract.
#include "bindings.hpp"

namespace legwork::py {

void bind_walkcycle(pb::module_& /*m*/) {}

}  // namespace legwork::py
