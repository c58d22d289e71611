// legwork.wip: bound once the wip runtime is on the per-frame contract.
#include "bindings.hpp"

namespace legwork::py {

void bind_wip(pb::module_& /*m*/) {}

}  // namespace legwork::py
