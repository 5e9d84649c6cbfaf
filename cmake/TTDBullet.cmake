# SPDX-License-Identifier: MIT
# Bullet (Debian's libbullet-dev, found through pkg-config) for the programs that run it beside
# ttd: include(TTDBullet) sets TTD_BULLET_FOUND and TTD_BULLET_VERSION and, when found, makes the
# imported target ttd::bullet (include folders and libraries) visible everywhere. Bullet is
# optional: a caller skips its program with a message when TTD_BULLET_FOUND is off. Used by
# examples/sim/bullet/ (the simulator's comparison); the scene benchmark may link the same target.
include_guard(GLOBAL)
set(TTD_BULLET_FOUND OFF)
set(TTD_BULLET_VERSION "")
find_package(PkgConfig QUIET)
if(PKG_CONFIG_FOUND)
  pkg_check_modules(TTD_BULLET_PC QUIET IMPORTED_TARGET GLOBAL bullet)
endif()
if(TARGET PkgConfig::TTD_BULLET_PC)
  set(TTD_BULLET_FOUND ON)
  set(TTD_BULLET_VERSION ${TTD_BULLET_PC_VERSION})
  if(NOT TARGET ttd::bullet)
    add_library(ttd::bullet ALIAS PkgConfig::TTD_BULLET_PC)
  endif()
endif()
