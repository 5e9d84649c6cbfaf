# SPDX-License-Identifier: MIT
# ttd.gpu_ptx (cmake -D PTX=a.ptx|b.ptx -P gpu_ptx.cmake): the device code's PTX, as
# src/gpu/CMakeLists.txt compiles it, rounds each operation as the CPU rows do (docs/gpu.md,
# section 2): no multiply-add or float FMA (contraction: the kernels' one explicit FMA is
# double, in kx_prod_err), no approximate division, reciprocal or square root, no flush to
# zero; and the double FMAs stay the explicit ones (12 per exact group inlined: the pair kernels
# and the mesh pose kernels of gpu_walk_impl.h inline 6 in gpu_d.ptx, 72 FMAs; the signed-distance
# kernel's ray count adds one in each file, its exact product error kept out of line,
# points/ray_impl.h's ray_prod_err; contraction makes hundreds: 790 in the pair kernels alone with
# -fmad=true). gpu_ccd.ptx (continuous collision, docs/ccd.md, section 14): its FMAs are the
# search's explicit fma() calls, each the exact error of a product.
string(REPLACE "|" ";" files "${PTX}")
foreach(f ${files})
  set(file_failed 0)
  file(READ "${f}" text)
  get_filename_component(name "${f}" NAME)
  foreach(bad "[ \t]mad\\.[a-z0-9.]*f(32|64)" "fma\\.rn\\.f32" "\\.ftz" "\\.approx" "div\\.full" "rsqrt")
    string(REGEX MATCHALL "${bad}" hits "${text}")
    list(LENGTH hits n)
    if(n GREATER 0)
      message(SEND_ERROR "${name}: ${n} instructions matching '${bad}'")
      set(file_failed 1)
    endif()
  endforeach()
  string(REGEX MATCHALL "fma\\.rn\\.f64" fmas "${text}")
  list(LENGTH fmas nfma)
  if(nfma GREATER 96)
    message(SEND_ERROR "${name}: ${nfma} fma.rn.f64: contraction?")
    set(file_failed 1)
  endif()
  string(REGEX MATCHALL "\\.entry" entries "${text}")
  list(LENGTH entries nentry)
  if(NOT file_failed)
    message(STATUS "${name}: ${nentry} kernels, ${nfma} fma.rn.f64 (the explicit ones), no contraction, approximation or flush to zero")
  endif()
  if(nentry EQUAL 0)
    message(SEND_ERROR "${name}: no kernel")
  endif()
endforeach()
