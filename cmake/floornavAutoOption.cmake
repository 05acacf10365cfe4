# Options that are AUTO (the default: on when what they need is found, also once it is installed
# into an existing build folder), ON (what they need is required) or OFF.

# floornav_auto_option(NAME DOC): the cache option NAME.
function(floornav_auto_option name doc)
  set(${name} AUTO CACHE STRING "${doc}: AUTO, ON or OFF")
  set_property(CACHE ${name} PROPERTY STRINGS AUTO ON OFF)
endfunction()

# floornav_resolve_auto_option(NAME FOUND NEEDS RESULT): RESULT is ON or OFF. With NAME ON and
# FOUND false, a fatal error says what is needed (NEEDS).
function(floornav_resolve_auto_option name found needs result)
  if(${name} STREQUAL "AUTO")
    set(value OFF)
    if(found)
      set(value ON)
    endif()
  elseif(${name})
    if(NOT found)
      message(FATAL_ERROR "${name}=ON needs ${needs}: not found")
    endif()
    set(value ON)
  else()
    set(value OFF)
  endif()
  set(${result} ${value} PARENT_SCOPE)
endfunction()
