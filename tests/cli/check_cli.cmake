# The command-line pipeline end to end: `obscura reference` writes EXR + JSON with a noise
# floor, `obscura bench` writes the CSV columns of the design map, and plot_report.py turns
# that into results.md with plots.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

include("${CMAKE_CURRENT_LIST_DIR}/run.cmake")

run("${OBSCURA}" reference --scene plane --size 16x12 --integrator ao --set radius=2 --spp 16 --quiet --halves
    --out "${WORK_DIR}/ao.exr")
foreach(f ao.exr ao.json ao.a.exr ao.b.exr)
  if(NOT EXISTS "${WORK_DIR}/${f}")
    message(FATAL_ERROR "obscura reference did not write ${f}")
  endif()
endforeach()
file(READ "${WORK_DIR}/ao.json" meta)
foreach(key noise_rmse noise_mse spp rays_per_second quantity)
  string(JSON value ERROR_VARIABLE missing GET "${meta}" ${key})
  if(missing)
    message(FATAL_ERROR "ao.json lacks ${key}: ${meta}")
  endif()
endforeach()

# A real HDR environment through a JSON scene: image-based light with visibility.
run("${OBSCURA}" reference --scene "${SOURCE_DIR}/scenes/wuson_forest.json" --size 16x12 --integrator ibl --spp 16
    --quiet --out "${WORK_DIR}/ibl.exr")
file(READ "${WORK_DIR}/ibl.json" meta)
string(JSON rays GET "${meta}" rays)
if(NOT rays GREATER 0)
  message(FATAL_ERROR "the IBL reference traced no rays: ${meta}")
endif()

# A bad integrator is refused with the list of known ones.
execute_process(COMMAND "${OBSCURA}" reference --scene plane --integrator nope --out "${WORK_DIR}/x.exr"
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(rc EQUAL 0 OR NOT err MATCHES "known:.*ao")
  message(FATAL_ERROR "an unknown integrator was not refused clearly: ${err}")
endif()

# The raw AO term as `obscura render` writes it (the issue's example command): one channel,
# finite, in [0, 1], 1 = unoccluded, darker with a longer radius. The Cornell box is in
# millimetres: within 0.5 mm almost nothing is in reach of the ray march (the mean stays within
# 1 % of 1: only pixels at the box's edges can darken); within 100 mm its corners and the
# blocks' feet are occluded. ao.voxel: the same term with voxel visibility, whose rays start a
# voxel diagonal (7.6 mm on the default 128^3 grid) off the surface, so that near the box's
# edges they start inside the other wall's voxels at any radius (about 2 % of this view).
# ARGN: more options (--camera).
function(ao_image_stats prefix technique radius)
  string(MAKE_C_IDENTIFIER "${technique}_${radius}_${ARGN}" stem)
  set(image "${WORK_DIR}/${stem}.exr")
  run("${OBSCURA}" render --scene cornell --size 64x48 --technique ${technique} --set radius=${radius} --set rays=64
      --set steps=32 --output ao --out "${image}" ${ARGN})
  execute_process(COMMAND "${OIIOTOOL}" --stats "${image}" RESULT_VARIABLE rc OUTPUT_VARIABLE info ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT info MATCHES "64 x +48, 1 channel")
    message(FATAL_ERROR "${image} is not a 64x48 one-channel image: ${info}${err}")
  endif()
  foreach(stat Min Max Avg NanCount InfCount)
    if(NOT info MATCHES "Stats ${stat}: ([-0-9.e+]+|-?nan|-?inf)")
      message(FATAL_ERROR "oiiotool gave no ${stat} for ${image}: ${info}")
    endif()
    set(${prefix}_${stat} ${CMAKE_MATCH_1} PARENT_SCOPE)
  endforeach()
endfunction()
foreach(technique ao.raymarch ao.voxel)
  ao_image_stats(near ${technique} 0.5)
  ao_image_stats(far ${technique} 100)
  set(ok FALSE)
  if(near_NanCount EQUAL 0 AND near_InfCount EQUAL 0 AND far_NanCount EQUAL 0 AND far_InfCount EQUAL 0 AND
     near_Min GREATER_EQUAL 0 AND far_Min GREATER_EQUAL 0 AND near_Max EQUAL 1 AND far_Max EQUAL 1 AND
     far_Avg LESS 0.95 AND near_Avg GREATER far_Avg)
    set(ok TRUE)
  endif()
  if(technique STREQUAL "ao.raymarch" AND NOT near_Avg GREATER 0.99)
    set(ok FALSE)
  endif()
  if(NOT ok)
    message(FATAL_ERROR "${technique} AO: radius 0.5 mm min ${near_Min} max ${near_Max} mean ${near_Avg} "
                        "(${near_NanCount} NaN, ${near_InfCount} Inf); radius 100 mm min ${far_Min} max ${far_Max} "
                        "mean ${far_Avg} (${far_NanCount} NaN, ${far_InfCount} Inf)")
  endif()
endforeach()
# The obscura CLI's --camera, as in the issue's example command (eye, target, up, vertical
# field of view in degrees): the Cornell box's own camera spelled out gives the same image;
# moved to 300 mm before the open side, where the view holds the box's corners and blocks
# larger, another.
ao_image_stats(scene ao.raymarch 100)
ao_image_stats(own ao.raymarch 100 --camera 278,273,-800,278,273,0,0,1,0,39.3077)
if(NOT own_Avg STREQUAL scene_Avg OR NOT own_Min STREQUAL scene_Min)
  message(FATAL_ERROR "--camera with the scene's own camera changed the AO: mean ${own_Avg} min ${own_Min}, "
                      "against ${scene_Avg} ${scene_Min} without it")
endif()
ao_image_stats(moved ao.raymarch 100 --camera 278,273,-300,278,273,0,0,1,0,39.3077)
if(moved_Avg STREQUAL scene_Avg OR NOT moved_NanCount EQUAL 0 OR NOT moved_Max EQUAL 1)
  message(FATAL_ERROR "--camera moved: mean ${moved_Avg} (${moved_NanCount} NaN, max ${moved_Max}), "
                      "against ${scene_Avg} from the scene's camera")
endif()
# Counts are whole numbers: a fraction is refused, not cut.
refused("rays=7.9.*whole number"
        "${OBSCURA}" render --scene cornell --size 8x8 --technique ao.raymarch --set rays=7.9 --out "${WORK_DIR}/x.exr")

# The gap between the depth layers (benchmarks/layer_gaps.sh): 0 where one is missing (the
# Cornell box's walls), nowhere longer than a path through the tall block (its space diagonal:
# a 166 mm square footprint, 330 mm high, 405 mm; the blocks are open at the floor), and asked
# for without the second layer, refused by name.
run("${OBSCURA}" render --scene cornell --size 64x48 --technique gbuffer --set depth_layers=2 --output layer_gap
    --out "${WORK_DIR}/layer_gap.exr")
execute_process(COMMAND "${OIIOTOOL}" --stats "${WORK_DIR}/layer_gap.exr" OUTPUT_VARIABLE info)
string(REGEX MATCH "Stats Min: ([-0-9.e+]+)" unused "${info}")
set(gapMin "${CMAKE_MATCH_1}")
string(REGEX MATCH "Stats Max: ([-0-9.e+]+)" unused "${info}")
set(gapMax "${CMAKE_MATCH_1}")
if(gapMin STREQUAL "" OR gapMax STREQUAL "" OR NOT gapMin EQUAL 0 OR NOT gapMax GREATER 0 OR gapMax GREATER 405
   OR NOT info MATCHES "NanCount: 0 ")
  message(FATAL_ERROR "layer_gap: expected 0 where a layer is missing, the largest gap in (0, 405] mm, no NaN: ${info}")
endif()
refused("layer_gap\" needs --set depth_layers=2"
        "${OBSCURA}" render --scene cornell --size 8x8 --technique gbuffer --output layer_gap --out "${WORK_DIR}/x.exr")

# Every technique into a directory (scripts/demo.sh's run): the outputs that need a setting
# the run does not have (layer_gap without the second layer, bent_normal without bent normals)
# are left out and named, the others all written.
file(MAKE_DIRECTORY "${WORK_DIR}/all")
execute_process(COMMAND "${OBSCURA}" render --scene cornell --size 16x12 --technique all --frames 1 --out "${WORK_DIR}/all"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "gbuffer +output layer_gap skipped: needs --set depth_layers=2")
  message(FATAL_ERROR "render --technique all into a directory failed or did not name the output it left out: ${out}${err}")
endif()
foreach(name gbuffer_depth gbuffer_normal ao.raymarch_ao ao.raymarch_bent_normal ao.voxel_ao gi.hybrid_indirect
             compose_radiance)
  if(NOT EXISTS "${WORK_DIR}/all/${name}.exr" OR NOT EXISTS "${WORK_DIR}/all/${name}.png")
    message(FATAL_ERROR "render --technique all wrote no ${name}.exr/.png")
  endif()
endforeach()
if(EXISTS "${WORK_DIR}/all/gbuffer_layer_gap.exr")
  message(FATAL_ERROR "render --technique all wrote layer_gap without the second layer")
endif()
# Compose's picture is display-encoded: a PNG only (an EXR is tagged linear), and refused as .exr.
if(NOT EXISTS "${WORK_DIR}/all/compose_image.png" OR EXISTS "${WORK_DIR}/all/compose_image.exr")
  message(FATAL_ERROR "compose's display picture: expected compose_image.png and no compose_image.exr")
endif()
refused("compose output image is a display picture.*\\.png"
        "${OBSCURA}" render --scene cornell --size 8x8 --technique compose --out "${WORK_DIR}/image.exr")
execute_process(COMMAND "${OBSCURA}" render --scene cornell --size 8x8 --technique ao.points --set bent_normals=0
                        --frames 1 --out "${WORK_DIR}/no_bent" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "output bent_normal skipped: needs --set bent_normals=1"
   OR NOT EXISTS "${WORK_DIR}/no_bent/ao.points_ao.exr" OR EXISTS "${WORK_DIR}/no_bent/ao.points_bent_normal.exr")
  message(FATAL_ERROR "bent_normals=0 into a directory: expected the AO alone and the bent normal named: ${out}${err}")
endif()
# --out is an image file or a directory: another extension is refused, not made a directory.
refused("not FILE.exr, FILE.png or a directory"
        "${OBSCURA}" render --scene cornell --size 8x8 --technique ao.points --out "${WORK_DIR}/ao.jpg")
if(EXISTS "${WORK_DIR}/ao.jpg")
  message(FATAL_ERROR "--out ao.jpg was refused but made")
endif()
# Ranges read as numbers: radius is more than 0, with no upper limit.
refused("radius=0: must be in \\(0, inf\\) world units"
        "${OBSCURA}" render --scene cornell --size 8x8 --technique ao.points --set radius=0 --out "${WORK_DIR}/x.exr")

# ambient is a colour too (r:g:b, as bench --variant can pass it): a red ambient term adds to
# the red channel of the combined radiance only.
foreach(ambient 0 0.5:0:0)
  run("${OBSCURA}" render --scene cornell --size 16x12 --technique compose --set formula=thesis --set gi=0
      --set ambient=${ambient} --output radiance --out "${WORK_DIR}/ambient_${ambient}.exr")
endforeach()
run("${OIIOTOOL}" "${WORK_DIR}/ambient_0.5:0:0.exr" "${WORK_DIR}/ambient_0.exr" --sub -o "${WORK_DIR}/ambient_diff.exr")
execute_process(COMMAND "${OIIOTOOL}" --stats "${WORK_DIR}/ambient_diff.exr" OUTPUT_VARIABLE info)
if(NOT info MATCHES "Stats Min: 0.0+ 0.0+ 0.0+" OR NOT info MATCHES "Stats Avg: 0.0*[1-9][0-9.e+-]* 0.0+ 0.0+")
  message(FATAL_ERROR "ambient=0.5:0:0 should raise the red channel alone: ${info}")
endif()
execute_process(COMMAND "${OBSCURA}" render --scene cornell --size 8x8 --technique compose --set ambient=0.1:0.2
                        --out "${WORK_DIR}/x.exr" RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(rc EQUAL 0 OR NOT err MATCHES "ambient=0.1:0.2.*r:g:b")
  message(FATAL_ERROR "ambient with two values was not refused clearly: ${err}")
endif()
# A bad component is named, with the value as given.
foreach(bad "0.1:x:0.2|g: not a number" "0.1:0.2:-1|b: must be in")
  string(REPLACE "|" ";" bad "${bad}")
  list(GET bad 0 value)
  list(GET bad 1 reason)
  execute_process(COMMAND "${OBSCURA}" render --scene cornell --size 8x8 --technique compose --set ambient=${value}
                          --out "${WORK_DIR}/x.exr" RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  string(FIND "${err}" "--set ambient=${value}: ${reason}" at)
  if(rc EQUAL 0 OR at EQUAL -1)
    message(FATAL_ERROR "ambient=${value} was not refused as '${reason}': ${err}")
  endif()
endforeach()

# A voxel grid's slices come 128 to a render target: other counts are refused by name.
execute_process(COMMAND "${OBSCURA}" render --scene cornell --size 8x8 --technique ao.voxel --set voxel_slices=200
                        --out "${WORK_DIR}/x.exr" RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(rc EQUAL 0 OR NOT err MATCHES "voxel_slices=200.*multiple of 128")
  message(FATAL_ERROR "voxel_slices=200 was not refused clearly: ${err}")
endif()

# voxel_resolution alone makes the grid cubic, also over a preset's larger grid (ultra: 1024^3),
# and voxel_slices holds in either order: the voxelizer's memory tells the grid apart.
function(voxelizer_bytes out)
  run("${OBSCURA}" bench --scene cornell --size 8x8 --frames 20 --spp 4 --techniques ao.voxel ${ARGN}
      --out "${WORK_DIR}/grid")
  file(READ "${WORK_DIR}/grid/bench.json" grid)
  string(JSON rows LENGTH "${grid}" rows)
  math(EXPR last "${rows} - 1")
  set(bytes "")
  foreach(i RANGE ${last})
    string(JSON b GET "${grid}" rows ${i} memory voxelizer)
    list(APPEND bytes ${b})
  endforeach()
  list(REMOVE_DUPLICATES bytes)
  set(${out} "${bytes}" PARENT_SCOPE)
endfunction()
voxelizer_bytes(cubic --presets low,ultra --set voxel_resolution=128)
voxelizer_bytes(slicesFirst --presets ultra --set voxel_slices=256 --set voxel_resolution=128)
voxelizer_bytes(slicesLast --presets ultra --set voxel_resolution=128 --set voxel_slices=256)
list(LENGTH cubic grids)
list(LENGTH slicesFirst firstGrids)
list(LENGTH slicesLast lastGrids)
if(NOT grids EQUAL 1 OR NOT firstGrids EQUAL 1 OR NOT lastGrids EQUAL 1 OR NOT slicesFirst EQUAL slicesLast OR
   NOT slicesFirst GREATER cubic)
  message(FATAL_ERROR "voxel grids: low and ultra at voxel_resolution=128 hold ${cubic} bytes, with 256 slices "
                      "${slicesFirst} (slices first) and ${slicesLast} (slices last)")
endif()

run("${OBSCURA}" bench --scene cornell --size 24x24 --frames 20 --spp 8 --out "${WORK_DIR}/bench" --images
    --voxels --voxel-triangles 3000 --voxel-resolutions 16 --voxel-targets 1,2 --voxel-segments 4096)
file(STRINGS "${WORK_DIR}/bench/bench.csv" csv)
list(GET csv 0 header)
foreach(col scene technique preset width height quantity clock gpu_ms cpu_ms rmse relmse ssim max_abs nan_count
            ref_noise_rmse false_shadow false_light umbra_leak memory_bytes)
  if(NOT "${header}" MATCHES "(^|,)${col}(,|$)")
    message(FATAL_ERROR "bench.csv lacks the column ${col}: ${header}")
  endif()
endforeach()
list(LENGTH csv lines)
if(lines LESS 2)
  message(FATAL_ERROR "bench.csv has no rows")
endif()
# Values: the G-buffer's rows have times > 0, no NaN in the output, and positions within a
# millimetre of the ray-traced hits (the Cornell box is in millimetres).
file(READ "${WORK_DIR}/bench/bench.json" bench)
string(JSON rows LENGTH "${bench}" rows)
math(EXPR last "${rows} - 1")
foreach(i RANGE ${last})
  string(JSON quantity GET "${bench}" rows ${i} quantity)
  string(JSON gpu GET "${bench}" rows ${i} gpu_ms)
  string(JSON nans GET "${bench}" rows ${i} nan_count)
  string(JSON rmse GET "${bench}" rows ${i} rmse)
  if(NOT gpu GREATER 0 OR NOT nans EQUAL 0)
    message(FATAL_ERROR "row ${i} (${quantity}): gpu_ms ${gpu}, nan_count ${nans}")
  endif()
  if(quantity STREQUAL "position" AND NOT rmse LESS 1)
    message(FATAL_ERROR "G-buffer positions are ${rmse} mm off the ray-traced hits")
  endif()
  # The hard shadow of the Cornell box's point light (cube maps) classifies most pixels right.
  string(JSON technique GET "${bench}" rows ${i} technique)
  string(JSON preset GET "${bench}" rows ${i} preset)
  set(hardPreset FALSE) # shadow.cube's medium_<filter> presets filter its maps
  if(NOT preset MATCHES "^medium_")
    set(hardPreset TRUE)
  endif()
  if(technique STREQUAL "shadow.cube" AND hardPreset)
    string(JSON falseShadow GET "${bench}" rows ${i} false_shadow)
    string(JSON falseLight GET "${bench}" rows ${i} false_light)
    if(NOT (falseShadow GREATER_EQUAL 0 AND falseShadow LESS 0.2 AND falseLight GREATER_EQUAL 0 AND falseLight LESS 0.2))
      message(FATAL_ERROR "shadow.cube row ${i}: false_shadow ${falseShadow}, false_light ${falseLight}")
    endif()
    set(sawShadow TRUE)
  endif()
  # Memory by pass: the maps pass holds at least the maps (six 32F layers for a cube, two for
  # paraboloids, of at least the smallest preset's 512^2 texels); a hard mask keeps nothing of
  # the light deep in the umbra.
  if(technique STREQUAL "shadow.cube" OR technique STREQUAL "shadow.paraboloid")
    string(JSON memory GET "${bench}" rows ${i} memory_bytes)
    string(JSON mapBytes GET "${bench}" rows ${i} memory shadow.maps)
    set(layers 6)
    if(technique STREQUAL "shadow.paraboloid")
      set(layers 2)
    endif()
    math(EXPR least "${layers} * 512 * 512 * 4")
    if(mapBytes LESS least OR memory LESS mapBytes)
      message(FATAL_ERROR "${technique} row ${i}: memory_bytes ${memory}, shadow_maps ${mapBytes}, expected >= ${least}")
    endif()
    string(JSON leak GET "${bench}" rows ${i} umbra_leak)
    if(hardPreset AND NOT leak STREQUAL "" AND NOT leak EQUAL 0)
      message(FATAL_ERROR "${technique} row ${i}: a hard mask leaks ${leak} into the umbra")
    endif()
  endif()
endforeach()
# --images: each measured output beside its reference, e.g. voxel AO at its largest grid.
foreach(image ao.voxel_ultra_ao ao.voxel_ultra_ao_reference gi.hybrid_low_indirect)
  if(NOT EXISTS "${WORK_DIR}/bench/images/cornell_${image}.exr")
    message(FATAL_ERROR "obscura bench --images wrote no images/cornell_${image}.exr")
  endif()
endforeach()
if(NOT sawShadow)
  message(FATAL_ERROR "the bench ran no shadow.cube row on the Cornell box")
endif()

# The voxelizer's tables: every configuration timed, (b) and (c) agreeing, (c) fetching less
# than (b) on the long segments.
string(JSON voxelRows LENGTH "${bench}" voxel voxelization)
if(NOT voxelRows EQUAL 4)
  message(FATAL_ERROR "expected 4 voxelization rows (2 modes x 1 resolution x 2 target counts), got ${voxelRows}")
endif()
string(JSON traversalRows LENGTH "${bench}" voxel traversal)
math(EXPR last "${traversalRows} - 1")
foreach(i RANGE ${last})
  string(JSON method GET "${bench}" voxel traversal ${i} method)
  string(JSON agree GET "${bench}" voxel traversal ${i} agrees_with_exact)
  string(JSON rate GET "${bench}" voxel traversal ${i} segments_per_second)
  if(NOT rate GREATER 0 OR (NOT method STREQUAL "march" AND NOT agree EQUAL 1))
    message(FATAL_ERROR "traversal row ${i} (${method}): ${rate} segments/s, agreement with exact ${agree}")
  endif()
endforeach()
foreach(table voxelization traversal)
  if(NOT EXISTS "${WORK_DIR}/bench/${table}.csv")
    message(FATAL_ERROR "obscura bench --voxels wrote no ${table}.csv")
  endif()
endforeach()

run("${PYTHON}" "${SOURCE_DIR}/benchmarks/plot_report.py" "${WORK_DIR}/bench/bench.json" --out "${WORK_DIR}/docs")
file(GLOB plots "${WORK_DIR}/docs/results/*.png")
if(NOT EXISTS "${WORK_DIR}/docs/results.md" OR NOT plots)
  message(FATAL_ERROR "plot_report.py wrote no results.md or no plots")
endif()
file(READ "${WORK_DIR}/docs/results.md" report)
if(NOT report MATCHES "## Voxelizer" OR NOT report MATCHES "## Visibility in voxel space")
  message(FATAL_ERROR "results.md lacks the voxelizer sections")
endif()

# Indirect light's own error ("indirect_unshadowed": against the gathering of unshadowed light)
# is measured only when the G-buffer it gathers is unshadowed too (shadows=0); with the default
# shadow-mapped G-buffer only "indirect", against the true one-bounce light.
foreach(shadows 1 0)
  run("${OBSCURA}" bench --scene cornell --size 8x8 --frames 20 --spp 4 --techniques gi.screen --presets low
      --set shadows=${shadows} --out "${WORK_DIR}/bench_gi_${shadows}")
  file(READ "${WORK_DIR}/bench_gi_${shadows}/bench.json" bench)
  string(JSON rowCount LENGTH "${bench}" rows)
  if(rowCount EQUAL 0)
    message(FATAL_ERROR "gi.screen with shadows=${shadows} measured nothing")
  endif()
  set(quantities "")
  math(EXPR last "${rowCount} - 1")
  foreach(i RANGE ${last})
    string(JSON quantity GET "${bench}" rows ${i} quantity)
    list(APPEND quantities ${quantity})
  endforeach()
  if(shadows)
    set(expected "indirect")
  else()
    set(expected "indirect;indirect_unshadowed")
  endif()
  if(NOT quantities STREQUAL expected)
    message(FATAL_ERROR "gi.screen with shadows=${shadows} measured ${quantities}, expected ${expected}")
  endif()
endforeach()

# A preset X and X_half take their timed frames in turn; each row's passes are still its own:
# every pass timed once per frame, and the filters only in the half-resolution row.
run("${OBSCURA}" bench --scene cornell --size 16x16 --frames 20 --spp 4 --techniques ao.points
    --presets medium_half,medium --set bent_normals=0 --out "${WORK_DIR}/bench_paired")
file(READ "${WORK_DIR}/bench_paired/bench.json" bench)
string(JSON rowCount LENGTH "${bench}" rows)
if(NOT rowCount EQUAL 2)
  message(FATAL_ERROR "medium and medium_half gave ${rowCount} rows, expected 2")
endif()
foreach(i 0 1)
  string(JSON preset GET "${bench}" rows ${i} preset)
  string(JSON passCount LENGTH "${bench}" rows ${i} passes)
  set(names "")
  math(EXPR lastPass "${passCount} - 1")
  foreach(j RANGE ${lastPass})
    string(JSON name GET "${bench}" rows ${i} passes ${j} pass)
    string(JSON samples GET "${bench}" rows ${i} passes ${j} samples)
    if(NOT samples EQUAL 20)
      message(FATAL_ERROR "${preset}: pass ${name} has ${samples} samples for 20 frames")
    endif()
    list(APPEND names ${name})
  endforeach()
  if(preset STREQUAL "medium" AND NOT names STREQUAL "gbuffer.render;ao.points")
    message(FATAL_ERROR "medium timed ${names}, expected gbuffer.render;ao.points")
  endif()
  list(FIND names ao.upsample upsample)
  if(preset STREQUAL "medium_half" AND upsample EQUAL -1)
    message(FATAL_ERROR "medium_half timed ${names}, without its upsampling")
  endif()
  # The counts beside the time: pixels with geometry (the box fills the 16x16 image); only the
  # half-resolution run asks for refinement, for at most those, and gets all it asked for, or
  # none past the list's 64 (a quarter of the pixels: so many edges at this size that it does).
  string(JSON geometry GET "${bench}" rows ${i} geometry_pixels)
  string(JSON asked GET "${bench}" rows ${i} refine_asked)
  string(JSON refined GET "${bench}" rows ${i} refined_pixels)
  set(granted ${asked})
  math(EXPR capacity "(16 * 16 + 3) / 4") # GuidedFilters::refineCapacity
  if(asked GREATER capacity)
    set(granted 0)
  endif()
  if(NOT geometry EQUAL 256 OR asked GREATER geometry OR NOT refined EQUAL granted OR
     (preset STREQUAL "medium" AND NOT asked EQUAL 0) OR (preset STREQUAL "medium_half" AND asked EQUAL 0))
    message(FATAL_ERROR "${preset}: ${refined} of ${asked} pixels refined, ${geometry} with geometry")
  endif()
endforeach()

# --variant: every preset runs once more with each variant's settings (a comma-separated list)
# after --set's, its frames timed in turn with the preset's own (20 samples per pass, as above),
# and its rows say so. The ray-lanes and geometry-tiles studies are such runs, each in a table
# of its own that compares only variants of its own setting.
run("${OBSCURA}" bench --scene cornell --size 16x16 --frames 20 --spp 4 --techniques ao.points
    --presets medium_half,medium --set bent_normals=0 --set ray_lanes=1 --variant ray_lanes=2
    --variant geometry_tiles=0 --variant geometry_tiles=0,blur_radius=1 --out "${WORK_DIR}/bench_variant")
file(READ "${WORK_DIR}/bench_variant/bench.json" bench)
string(JSON rowCount LENGTH "${bench}" rows)
if(NOT rowCount EQUAL 8)
  message(FATAL_ERROR "medium and medium_half with three variants gave ${rowCount} rows, expected 8")
endif()
set(seen "")
foreach(i RANGE 7)
  string(JSON preset GET "${bench}" rows ${i} preset)
  string(JSON variant GET "${bench}" rows ${i} variant)
  string(JSON got GET "${bench}" rows ${i} settings)
  string(JSON samples GET "${bench}" rows ${i} passes 0 samples)
  if(variant STREQUAL "")
    set(expected "ray_lanes=1")
  elseif(variant STREQUAL "ray_lanes=2")
    set(expected "ray_lanes=2")
  elseif(variant STREQUAL "geometry_tiles=0")
    set(expected "ray_lanes=1;geometry_tiles=0")
  elseif(variant STREQUAL "geometry_tiles=0,blur_radius=1")
    set(expected "ray_lanes=1;geometry_tiles=0;blur_radius=1")
  else()
    message(FATAL_ERROR "${preset}: unexpected variant '${variant}'")
  endif()
  list(APPEND expected "bent_normals=0")
  foreach(kv ${expected})
    string(REPLACE "=" ";" kv "${kv}")
    list(GET kv 0 key)
    list(GET kv 1 value)
    string(JSON actual ERROR_VARIABLE missing GET "${got}" ${key})
    if(missing OR NOT actual STREQUAL value)
      message(FATAL_ERROR "${preset} (variant '${variant}') ran with settings ${got}, expected ${key}=${value}")
    endif()
  endforeach()
  if(NOT samples EQUAL 20)
    message(FATAL_ERROR "${preset} (variant '${variant}'): ${samples} samples for 20 frames")
  endif()
  list(APPEND seen "${preset}/${variant}")
endforeach()
list(REMOVE_DUPLICATES seen)
list(LENGTH seen distinct)
if(NOT distinct EQUAL 8)
  message(FATAL_ERROR "the rows are not one per preset and variant: ${seen}")
endif()
file(STRINGS "${WORK_DIR}/bench_variant/bench.csv" csv)
list(GET csv 0 header)
if(NOT header MATCHES ",variant$")
  message(FATAL_ERROR "bench.csv lacks the variant column: ${header}")
endif()
run("${PYTHON}" "${SOURCE_DIR}/benchmarks/plot_report.py" "${WORK_DIR}/bench/bench.json"
    --lanes-study "${WORK_DIR}/bench_variant/bench.json" --tiles-study "${WORK_DIR}/bench_variant/bench.json"
    --out "${WORK_DIR}/docs_variant")
file(READ "${WORK_DIR}/docs_variant/results.md" report)
if(NOT report MATCHES "## Ray lanes" OR NOT report MATCHES "\\| cornell \\| 16x16 \\| ao.points \\| ao \\| medium \\|")
  message(FATAL_ERROR "results.md lacks the ray-lanes table or its ao.points row")
endif()
if(NOT report MATCHES "## Geometry tiles" OR NOT report MATCHES "\\| cornell \\| 16x16 \\| ao.points \\| ao \\| medium_half \\|")
  message(FATAL_ERROR "results.md lacks the geometry-tiles table or its ao.points medium_half row")
endif()
# A results.md table row's cells, without the row's outer bars, so that no list element is
# empty (which CMP0007, unset in script mode, would drop); fails unless there are `count`.
function(row_cells row count outVar)
  string(REGEX REPLACE "^\\| (.*) \\|$" "\\1" inner "${row}")
  string(REPLACE " | " ";" cells "${inner}")
  list(LENGTH cells cellCount)
  if(NOT cellCount EQUAL count)
    message(FATAL_ERROR "a table row should have ${count} cells, has ${cellCount}: ${row}")
  endif()
  set(${outVar} "${cells}" PARENT_SCOPE)
endfunction()
# The geometry-tiles table pairs the preset with geometry_tiles=0 alone, not with the variant that
# also blurs otherwise: one row per preset, and (bit-identical results) equal RMSEs.
string(REGEX MATCHALL "\\| cornell \\| 16x16 \\| ao.points \\| ao \\| medium_half \\|[^\n]*" tileRows "${report}")
list(LENGTH tileRows tileRowCount)
if(NOT tileRowCount EQUAL 1)
  message(FATAL_ERROR "the geometry-tiles table has ${tileRowCount} medium_half rows, expected 1: ${tileRows}")
endif()
row_cells("${tileRows}" 10 cells)
list(GET cells 8 a) # RMSE, every tile
list(GET cells 9 b) # RMSE, geometry tiles
if(NOT a STREQUAL b)
  message(FATAL_ERROR "the geometry-tiles table's RMSEs differ (${a} and ${b}): ${tileRows}")
endif()
# The thickness study: each preset with depth peeling, the deeper of both and a set thickness
# beside it, one table row per preset with all five RMSEs.
run("${OBSCURA}" bench --scene cornell --size 16x16 --frames 20 --spp 4 --techniques ao.points --presets low,medium
    --variant thickness_mode=depth_peeling --variant thickness_mode=peeling_or_constant --variant thickness=10
    --variant thickness_mode=peeling_or_constant,thickness=10 --out "${WORK_DIR}/bench_thickness")
run("${PYTHON}" "${SOURCE_DIR}/benchmarks/plot_report.py" "${WORK_DIR}/bench/bench.json"
    --thickness-study "${WORK_DIR}/bench_thickness/bench.json" --out "${WORK_DIR}/docs_thickness")
file(READ "${WORK_DIR}/docs_thickness/results.md" report)
string(REGEX MATCHALL "\\| cornell \\| 16x16 \\| ao.points \\| (low|medium) \\|[^\n]*" thicknessRows "${report}")
list(LENGTH thicknessRows thicknessRowCount)
if(NOT report MATCHES "## Screen-space thickness" OR NOT thicknessRowCount EQUAL 2)
  message(FATAL_ERROR "results.md lacks the thickness table or its two ao.points rows: ${thicknessRows}")
endif()
foreach(thicknessRow IN LISTS thicknessRows)
  # The last five cells: constant, peeling, deeper of both, and the two with thickness=10.
  if(NOT thicknessRow MATCHES "\\| [0-9][0-9.e+-]* \\| [0-9][0-9.e+-]* \\| [0-9][0-9.e+-]* \\| [0-9][0-9.e+-]* \\| [0-9][0-9.e+-]* \\|$")
    message(FATAL_ERROR "a thickness row lacks one of its five RMSEs: ${thicknessRow}")
  endif()
endforeach()
# The falloff study: each obscurance preset with the four falloffs, one row each with four
# times and four RMSEs, each against the reference with its own falloff (so they differ).
run("${OBSCURA}" bench --scene cornell --size 16x16 --frames 20 --spp 4 --techniques obscurance.points --presets low
    --variant falloff=none --variant falloff=quadratic --variant falloff=smooth --out "${WORK_DIR}/bench_falloff")
run("${PYTHON}" "${SOURCE_DIR}/benchmarks/plot_report.py" "${WORK_DIR}/bench/bench.json"
    --falloff-study "${WORK_DIR}/bench_falloff/bench.json" --out "${WORK_DIR}/docs_falloff")
file(READ "${WORK_DIR}/docs_falloff/results.md" report)
string(REPEAT "\\| [0-9][0-9.e+-]* " 8 eightNumbers) # CMake's regex has no {8}
string(REGEX MATCH "\\| cornell \\| 16x16 \\| obscurance.points \\| low \\|[^\n]*" falloffRow "${report}")
if(NOT report MATCHES "## Obscurance falloffs" OR NOT falloffRow MATCHES "low ${eightNumbers}\\|$")
  message(FATAL_ERROR "results.md lacks the falloff table's row with four times and four RMSEs: '${falloffRow}'")
endif()
# Scene, size, technique, preset, four times, four RMSEs.
row_cells("${falloffRow}" 12 cells)
list(SUBLIST cells 8 4 rmses)
list(REMOVE_DUPLICATES rmses)
list(LENGTH rmses distinct)
if(distinct LESS 3)
  message(FATAL_ERROR "the falloffs' RMSEs should differ: ${falloffRow}")
endif()
# The quarter-resolution study from a real bench: X and X_half, both also at quarter
# resolution, in one row of numbers (four times, four RMSEs, speed-ups and the filters' time);
# the half-resolution table keeps its own row (no variant). check_report_tables.py checks
# which run each cell comes from.
run("${OBSCURA}" bench --scene cornell --size 32x32 --frames 20 --spp 4 --techniques ao.points
    --presets medium,medium_half --set bent_normals=0 --variant resolution=quarter --out "${WORK_DIR}/bench_quarter")
run("${PYTHON}" "${SOURCE_DIR}/benchmarks/plot_report.py" "${WORK_DIR}/bench/bench.json"
    --resolution-study "${WORK_DIR}/bench_quarter/bench.json" --out "${WORK_DIR}/docs_quarter")
file(READ "${WORK_DIR}/docs_quarter/results.md" report)
string(REGEX MATCH "## Quarter resolution[^#]*" quarterTable "${report}")
string(REGEX MATCHALL "\\| cornell \\| 32x32 \\| medium \\| ao.points \\| ao \\|[^\n]*" quarterRows "${quarterTable}")
list(LENGTH quarterRows quarterRowCount)
if(NOT quarterRowCount EQUAL 1)
  message(FATAL_ERROR "the quarter-resolution table should have one ao.points row: '${quarterRows}'")
endif()
row_cells("${quarterRows}" 17 cells)
foreach(i RANGE 5 16)
  list(GET cells ${i} cell)
  if(NOT cell MATCHES "^[0-9][0-9.e+-]*$")
    message(FATAL_ERROR "quarter-resolution cell ${i} is not a number: ${quarterRows}")
  endif()
endforeach()
# Half and quarter resolution, and quarter resolution with and without the blur, are
# different computations: equal RMSEs would mean two columns read the same run.
list(GET cells 12 halfRmse)
list(GET cells 13 quarterRmse)
list(GET cells 16 bareRmse)
if(halfRmse STREQUAL quarterRmse OR quarterRmse STREQUAL bareRmse)
  message(FATAL_ERROR "the quarter-resolution row repeats an RMSE: ${quarterRows}")
endif()
string(REGEX MATCHALL "\\| cornell \\| 32x32 \\| medium \\| ao.points \\| ao \\|" anyRows "${report}")
list(LENGTH anyRows anyRowCount)
if(NOT anyRowCount EQUAL 2)
  message(FATAL_ERROR "results.md should show ao.points medium at 32x32 once at half and once at quarter resolution")
endif()
# The refinement study from a real bench: one row of X, X_half and X_half without refinement
# (three numbers, the refined pixels of the geometry's, six numbers, two verdicts);
# check_report_tables.py checks which run each cell comes from.
run("${OBSCURA}" bench --scene cornell --size 32x32 --frames 20 --spp 4 --techniques ao.points
    --presets medium,medium_half --set bent_normals=0 --variant refine_threshold=0 --out "${WORK_DIR}/bench_refine")
run("${PYTHON}" "${SOURCE_DIR}/benchmarks/plot_report.py" "${WORK_DIR}/bench/bench.json"
    --refine-study "${WORK_DIR}/bench_refine/bench.json" --out "${WORK_DIR}/docs_refine")
file(READ "${WORK_DIR}/docs_refine/results.md" report)
string(REPEAT "\\| [0-9][0-9.e+-]* " 3 threeNumbers)
string(REPEAT "\\| [0-9][0-9.e+-]* " 6 sixNumbers)
string(REGEX MATCH "## Refinement at half resolution[^#]*" refineTable "${report}")
string(REGEX MATCH "\\| cornell \\| 32x32 \\| medium \\| ao.points \\| ao ${threeNumbers}\\| ([0-9]+ of [1-9][0-9]* \\([0-9]+%\\)|none: [0-9]+ asked, over the list) ${sixNumbers}\\| [*a-z]+ \\| [*a-z]+ \\|"
       refineRow "${refineTable}")
if(NOT refineRow)
  message(FATAL_ERROR "results.md lacks the refinement table's ao.points row: three numbers, the refined pixels of "
                      "the geometry's, six numbers and two verdicts")
endif()
execute_process(COMMAND "${OBSCURA}" bench --scene cornell --size 8x8 --techniques ao.points --presets medium
                        --variant ray_lanes=2 --variant ray_lanes=2 --out "${WORK_DIR}/bench_bad_variant"
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(rc EQUAL 0 OR NOT err MATCHES "each variant must be a new")
  message(FATAL_ERROR "bench with a repeated --variant was not refused clearly: ${err}")
endif()

# --set overrides every preset's settings (here the maps' size: six 256^2 32F layers, plus the
# lights' records, a few KiB; the low preset's own 512^2 maps would be four times as much),
# and --no-cache leaves no reference files behind.
run("${OBSCURA}" bench --scene cornell --size 24x24 --frames 20 --spp 8 --techniques shadow.cube --presets low
    --set resolution=256 --no-cache --out "${WORK_DIR}/bench_set")
file(READ "${WORK_DIR}/bench_set/bench.json" bench)
string(JSON mapBytes GET "${bench}" rows 0 memory shadow.maps)
math(EXPR expected "6 * 256 * 256 * 4")
math(EXPR ceiling "${expected} + 65536")
if(mapBytes LESS expected OR NOT mapBytes LESS ceiling)
  message(FATAL_ERROR "bench --set resolution=256: shadow.maps holds ${mapBytes} bytes, expected ${expected}")
endif()
if(EXISTS "${WORK_DIR}/bench_set/reference-cache")
  message(FATAL_ERROR "bench --no-cache wrote a reference cache")
endif()
execute_process(COMMAND "${OBSCURA}" bench --scene cornell --size 8x8 --techniques shadow.cube --presets low
                        --set resolution --out "${WORK_DIR}/bench_bad"
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(rc EQUAL 0 OR NOT err MATCHES "key=value")
  message(FATAL_ERROR "bench --set without a value was not refused clearly: ${err}")
endif()
