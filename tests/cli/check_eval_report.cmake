# Checks the structure of a `legwork eval accent --quick` report and that the
# engine beats nearest-neighbour-without-alignment on it.
# Usage: cmake -DREPORT_DIR=dir -P check_eval_report.cmake
file(READ ${REPORT_DIR}/report.json report)
foreach(f report.md body_parts.png body_parts.svg classes.png classes.svg ablation.png ablation.svg)
  if(NOT EXISTS ${REPORT_DIR}/${f})
    message(FATAL_ERROR "missing ${REPORT_DIR}/${f}")
  endif()
endforeach()

set(keys full_body_cm upper_body_cm lower_body_cm left_hand_cm right_hand_cm hand_correlation mpjve_cm_s jitter
         frames_per_second)
function(require_number)
  string(JSON type ERROR_VARIABLE err TYPE "${report}" ${ARGN})
  if(err OR NOT type STREQUAL "NUMBER")
    string(REPLACE ";" "." where "${ARGN}")
    message(FATAL_ERROR "report.json: ${where} is not a number (${type}${err})")
  endif()
endfunction()

foreach(protocol cross_subject cross_trial)
  foreach(method accent ik ik_own)
    foreach(k IN LISTS keys)
      require_number(${protocol} ${method} ${k})
    endforeach()
    # Per class: the same figures (frames_per_second too).
    string(JSON nclass LENGTH "${report}" ${protocol} ${method} classes)
    if(nclass LESS 1)
      message(FATAL_ERROR "report.json: ${protocol}.${method}.classes is empty")
    endif()
    math(EXPR last "${nclass} - 1")
    foreach(i RANGE ${last})
      string(JSON cls MEMBER "${report}" ${protocol} ${method} classes ${i})
      foreach(k IN LISTS keys)
        require_number(${protocol} ${method} classes ${cls} ${k})
      endforeach()
    endforeach()
  endforeach()
endforeach()

# The document's figures are there to print beside ours.
require_number(paper cross_subject accent full_body_cm)
require_number(paper ablation nn)

# The engine must beat plain nearest neighbour (no alignment, no smoothing).
require_number(cross_subject ablation nn full_body_cm)
require_number(cross_subject ablation accent full_body_cm)
string(JSON nn GET "${report}" cross_subject ablation nn full_body_cm)
string(JSON engine GET "${report}" cross_subject ablation accent full_body_cm)
if(NOT engine LESS nn)
  message(FATAL_ERROR "engine full-body error ${engine} cm is not below NN-without-alignment ${nn} cm")
endif()
string(JSON ntargets LENGTH "${report}" targets)
if(ntargets LESS 5)
  message(FATAL_ERROR "report.json: only ${ntargets} targets")
endif()
message(STATUS "quick report OK: engine ${engine} cm < NN ${nn} cm; ${ntargets} targets evaluated")
