# syncap_target_warnings(<target>): the project's warning set, as errors when SYNCAP_WERROR is on.
function(syncap_target_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wformat=2 -Wundef
    $<$<COMPILE_LANGUAGE:C>:-Wstrict-prototypes -Wmissing-prototypes>
    $<$<COMPILE_LANGUAGE:CXX>:-Wnon-virtual-dtor -Woverloaded-virtual>
    $<$<BOOL:${SYNCAP_WERROR}>:-Werror>)
endfunction()
