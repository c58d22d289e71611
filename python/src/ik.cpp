// legwork.ik: bound once the ik runtime is on the per-frame contract.
#include "bindings.hpp"

namespace legwork::py {

void bind_ik(pb::module_& /*m*/) {}

}  // namespace legwork::py
