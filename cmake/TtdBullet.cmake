# SPDX-License-Identifier: MIT
# Finds Bullet 3 (the collision library, for programs that compare with it) through pkg-config:
# the double-precision build (`bullet-float64`, Debian's libbullet-dev ships it beside the float
# one) when it is there, else the float one (`bullet`). Defines, when found:
#   ttd::bullet              an imported interface target (include folders, BT_USE_DOUBLE_PRECISION
#                            where it applies, the BulletCollision and LinearMath libraries)
#   TTD_BULLET_FOUND         TRUE
#   TTD_BULLET_PRECISION     "double" or "float"
#   TTD_BULLET_VERSION       as pkg-config reports it
# and otherwise TTD_BULLET_FOUND FALSE, silently: the caller says what is left out.
# Usage: include(TtdBullet) (with cmake/ on CMAKE_MODULE_PATH), then if(TTD_BULLET_FOUND).
set(TTD_BULLET_FOUND FALSE)
if(NOT TARGET ttd::bullet)
  find_package(PkgConfig QUIET)
  if(PKG_CONFIG_FOUND)
    foreach(module bullet-float64 bullet)
      pkg_check_modules(TTD_BULLET_PC QUIET ${module})
      if(TTD_BULLET_PC_FOUND)
        # only the collision part: the dynamics and soft bodies of the .pc file are not needed
        set(libs)
        foreach(part BulletCollision LinearMath)
          set(name ${part})
          if(module STREQUAL "bullet-float64")
            set(name ${part}-float64)
          endif()
          find_library(TTD_BULLET_LIB_${part}_${module} NAMES ${name} HINTS ${TTD_BULLET_PC_LIBRARY_DIRS})
          if(TTD_BULLET_LIB_${part}_${module})
            list(APPEND libs ${TTD_BULLET_LIB_${part}_${module}})
          endif()
        endforeach()
        list(LENGTH libs nlibs)
        if(nlibs EQUAL 2)
          add_library(ttd::bullet INTERFACE IMPORTED)
          set_target_properties(ttd::bullet PROPERTIES
              INTERFACE_INCLUDE_DIRECTORIES "${TTD_BULLET_PC_INCLUDE_DIRS}"
              INTERFACE_COMPILE_OPTIONS "${TTD_BULLET_PC_CFLAGS_OTHER}"
              INTERFACE_LINK_LIBRARIES "${libs}")
          if(module STREQUAL "bullet-float64")
            set(TTD_BULLET_PRECISION double CACHE INTERNAL "")
          else()
            set(TTD_BULLET_PRECISION float CACHE INTERNAL "")
          endif()
          set(TTD_BULLET_VERSION ${TTD_BULLET_PC_VERSION} CACHE INTERNAL "")
          break()
        endif()
      endif()
      unset(TTD_BULLET_PC_FOUND CACHE)
    endforeach()
  endif()
endif()
if(TARGET ttd::bullet)
  set(TTD_BULLET_FOUND TRUE)
endif()
