# `--set` keys: every field of a settings struct is a key of its module's techniques; each
# technique lists, and takes, only the keys its method reads (another method's is refused,
# naming the techniques that have it, by render and, before anything runs, by bench); and a
# key that has no effect with the run's other settings is named in a note.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

include("${CMAKE_CURRENT_LIST_DIR}/run.cmake")
cmake_policy(SET CMP0057 NEW) # if(IN_LIST) in script mode

execute_process(COMMAND "${OBSCURA}" info OUTPUT_VARIABLE info RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "obscura info failed")
endif()
# As a CMake list: no ';', and no unbalanced '[' (it would join the lines that follow).
string(REGEX REPLACE "[];[]" "," info "${info}")
string(REPLACE "\n" ";" info_lines "${info}")

# listed_keys(technique out): the `--set` keys `obscura info` lists for a technique.
function(listed_keys technique out)
  set(listed "")
  set(current "")
  foreach(line IN LISTS info_lines)
    if(line MATCHES "^  ([^ ]+) ")
      set(current "${CMAKE_MATCH_1}")
    elseif(current STREQUAL technique AND line MATCHES "--set ([a-z_]+) ")
      list(APPEND listed "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  set(${out} "${listed}" PARENT_SCOPE)
endfunction()

# The field names (read from the header) in snake case are keys of one of `techniques` at
# least, but for those in `skip` (the method, which the technique's name picks; the voxel grid,
# which the CLI builds from the voxel_* keys).
function(check_settings_keys header struct techniques skip)
  file(READ "${SOURCE_DIR}/include/obscura/${header}" text)
  string(REGEX REPLACE "[];[]" "," text "${text}")
  string(FIND "${text}" "struct ${struct} {" begin)
  if(begin EQUAL -1)
    message(FATAL_ERROR "${header} has no struct ${struct}")
  endif()
  string(SUBSTRING "${text}" ${begin} -1 text)
  string(FIND "${text}" "\n}," end) # the struct's closing "};", its ';' replaced
  string(SUBSTRING "${text}" 0 ${end} body)
  set(field_regex "\n    (const )?[A-Za-z0-9_:<>]+\\*? +([a-z][A-Za-z0-9]*) *[=,{]")
  string(REGEX MATCHALL "${field_regex}" fields "${body}")
  # Every line at the members' indent that is not a comment declares one: a field the regex
  # above did not read (a type it does not know, two names in one line) fails here.
  string(REGEX MATCHALL "\n    [^/ \n][^\n]*" declarations "${body}")
  list(FILTER declarations EXCLUDE REGEX "^\n    static ") # the table's accessor
  list(LENGTH declarations declared)
  set(listed "")
  foreach(technique IN LISTS techniques)
    listed_keys(${technique} keys)
    if(NOT keys)
      message(FATAL_ERROR "obscura info lists no keys for ${technique}")
    endif()
    list(APPEND listed ${keys})
  endforeach()
  list(LENGTH fields count)
  if(count LESS 5 OR NOT count EQUAL declared)
    message(FATAL_ERROR "${struct}: read ${count} fields of ${declared} declarations (${declarations})")
  endif()
  foreach(field IN LISTS fields)
    string(REGEX REPLACE "${field_regex}" "\\2" name "${field}")
    if(name IN_LIST skip)
      continue()
    endif()
    string(REGEX REPLACE "([A-Z])" "_\\1" key "${name}")
    string(TOLOWER "${key}" key)
    if(NOT key IN_LIST listed)
      message(FATAL_ERROR "${struct}::${name} has no key ${key} in ${techniques} (keys: ${listed})")
    endif()
  endforeach()
endfunction()
check_settings_keys(ambient_occlusion.hpp AmbientOcclusionSettings "ao.raymarch;ao.voxel" "method;voxels")
check_settings_keys(indirect_light.hpp IndirectLightSettings "gi.screen;gi.hybrid" "method;voxels")
check_settings_keys(compose.hpp ComposeSettings compose "")
check_settings_keys(shadow_maps.hpp ShadowMapSettings "shadow.hard" "pointMapping")
check_settings_keys(shadow_maps.hpp ShadowMaskSettings "shadow.hard;shadow.cube" "")

# The keys a method does not read, as the settings' docs say (ambient_occlusion.hpp: steps
# are RayMarch's, Horizon's and the voxel march's, thickness and its mode RayMarch's and
# Points', march RayMarch's, Horizon is cosine-weighted AO only; indirect_light.hpp: the
# hybrid method's rays test voxels), are not listed.
function(check_unlisted technique)
  listed_keys(${technique} keys)
  if(NOT keys)
    message(FATAL_ERROR "obscura info lists no keys for ${technique}")
  endif()
  foreach(key IN LISTS ARGN)
    if(key IN_LIST keys)
      message(FATAL_ERROR "${technique} lists ${key}, which it does not read (keys: ${keys})")
    endif()
  endforeach()
endfunction()
set(voxel_keys voxel_resolution voxel_slices voxel_traversal)
check_unlisted(ao.raymarch ${voxel_keys})
check_unlisted(ao.points steps march ${voxel_keys})
check_unlisted(obscurance.points steps march ${voxel_keys})
check_unlisted(ao.horizon cosine_weighted falloff thickness thickness_mode march ${voxel_keys})
check_unlisted(ao.voxel thickness thickness_mode march)
check_unlisted(obscurance.voxel thickness thickness_mode march)
check_unlisted(gi.screen ${voxel_keys})
check_unlisted(gi.hybrid thickness_mode march)
# shadow_maps.hpp: a technique named for its filter takes no `filter` and no other filter's
# keys (pcf_radius and pcf_kernel are PCF's, receiver_plane PCF's and PCSS's, the prefilter the
# moment filters', the Chebyshev bound's VSM's and EVSM's, the exponents ESM's and EVSM's); a
# point light's techniques take no cascades.
check_unlisted(shadow.hard filter pcf_radius pcf_kernel receiver_plane pcss_blocker_fraction moment_blur min_variance
               exponent negative_exponent)
check_unlisted(shadow.vsm filter pcf_radius receiver_plane exponent negative_exponent)
check_unlisted(shadow.esm filter min_variance light_bleed_reduction negative_exponent)
check_unlisted(shadow.msm filter min_variance exponent)
check_unlisted(shadow.pcss filter pcf_radius moment_blur cascades split_lambda reflective depth_bounds cascade_blend)
check_unlisted(shadow.cube cascades split_lambda reflective depth_bounds cascade_blend)

# And each listed key is taken: every one set at once (values inside their ranges).
run("${OBSCURA}" render --scene cornell --size 16x12 --technique ao.raymarch --set radius=100 --set rays=4 --set steps=4
    --set cosine_weighted=0 --set falloff=linear --set thickness=20 --set thickness_mode=constant --set march=texture
    --set resolution=half --set blur_radius=1 --set blur_depth_sigma=0.1 --set blur_normal_power=8
    --set refine_threshold=0.5 --set ray_lanes=2 --set geometry_tiles=0 --set bent_normals=0
    --out "${WORK_DIR}/ao_keys.exr")
run("${OBSCURA}" render --scene cornell --size 16x12 --technique ao.voxel --set radius=100 --set rays=4 --set steps=4
    --set cosine_weighted=0 --set falloff=linear --set resolution=half --set blur_radius=1 --set blur_depth_sigma=0.1
    --set blur_normal_power=8 --set refine_threshold=0.5 --set ray_lanes=2 --set geometry_tiles=0 --set bent_normals=0
    --set voxel_resolution=64 --set voxel_slices=128 --set voxel_traversal=march --out "${WORK_DIR}/ao_voxel_keys.exr")
run("${OBSCURA}" render --scene cornell --size 16x12 --technique gi.screen --set radius=100 --set rays=4 --set steps=4
    --set thickness=20 --set thickness_mode=constant --set march=texture --set resolution=half --set blur_radius=1
    --set blur_depth_sigma=0.1 --set blur_normal_power=8 --set refine_threshold=0.5 --set ray_lanes=2
    --set geometry_tiles=0 --set shadows=1 --set shadow_resolution=64 --set shadow_filter=hard --out "${WORK_DIR}/gi_keys.exr")
run("${OBSCURA}" render --scene cornell --size 16x12 --technique gi.hybrid --set thickness=20 --set steps=4
    --set voxel_resolution=64 --set voxel_slices=128 --set voxel_traversal=march --out "${WORK_DIR}/gi_hybrid_keys.exr")
# Compose's keys, each set.
run("${OBSCURA}" render --scene cornell --size 16x12 --technique compose --set formula=thesis --set ambient=0.1
    --set indirect_scale=0.5 --set exposure=0.05 --set tone_mapper=drago --set drago_max_luminance=5 --set drago_bias=0.7
    --set drago_display_max=200 --set srgb=0 --set gamma=1.8 --out "${WORK_DIR}/compose.png")

# Another method's key is refused, not ignored, and the message says who has it.
refused("ao.points has no setting \"steps\" \\(ao.horizon, ao.raymarch, ao.voxel, .*have it\\); its settings: radius, rays,"
        "${OBSCURA}" render --scene cornell --size 8x8 --technique ao.points --set steps=4 --out "${WORK_DIR}/x.exr")
refused("ao.raymarch has no setting \"voxel_traversal\" \\(ao.voxel, gi.hybrid, obscurance.voxel have it\\)"
        "${OBSCURA}" render --scene cornell --size 8x8 --technique ao.raymarch --set voxel_traversal=exact
        --out "${WORK_DIR}/x.exr")
refused("gi.hybrid has no setting \"march\""
        "${OBSCURA}" render --scene cornell --size 8x8 --technique gi.hybrid --set march=hiz --out "${WORK_DIR}/x.exr")
refused("shadow.hard has no setting \"filter\" \\(shadow.cube, shadow.paraboloid have it\\)"
        "${OBSCURA}" render --scene cornell --size 8x8 --technique shadow.hard --set filter=pcf --out "${WORK_DIR}/x.exr")
# bench refuses it before the first scene runs, for --set and --variant alike.
foreach(option --set --variant)
  execute_process(COMMAND "${OBSCURA}" bench --scene cornell --size 8x8 --frames 20 --spp 4 --techniques "ao.*"
                          ${option} march=hiz --out "${WORK_DIR}/bench_refused"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT err MATCHES "ao.horizon has no setting \"march\"" OR out MATCHES "scene cornell")
    message(FATAL_ERROR "bench ${option} march=hiz over ao.*: not refused before running: ${out}${err}")
  endif()
endforeach()

# expect_note(PATTERN|"" COMMAND...): the command succeeds, and its notes match PATTERN (a
# regex), or with "" it prints none.
function(expect_note pattern)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(all "${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${all}")
  elseif(pattern STREQUAL "" AND all MATCHES "note:")
    message(FATAL_ERROR "a note where none was due: ${ARGN}\n${all}")
  elseif(NOT pattern STREQUAL "" AND NOT all MATCHES "${pattern}")
    message(FATAL_ERROR "no note '${pattern}': ${ARGN}\n${all}")
  endif()
endfunction()
set(render "${OBSCURA}" render --scene cornell --size 8x8 --frames 1)
expect_note("note: ao.voxel ignores --set steps=4: read only with voxel_traversal=march"
            ${render} --technique ao.voxel --set steps=4 --out "${WORK_DIR}/x.exr")
expect_note("" ${render} --technique ao.voxel --set steps=4 --set voxel_traversal=march --out "${WORK_DIR}/x.exr")
expect_note("note: ao.raymarch ignores --set refine_threshold=0: read only at resolution half or quarter"
            ${render} --technique ao.raymarch --set refine_threshold=0 --out "${WORK_DIR}/x.exr")
expect_note("" ${render} --technique ao.raymarch --set refine_threshold=0 --set resolution=half --out "${WORK_DIR}/x.exr")
expect_note("note: gi.screen ignores --set blur_normal_power=4: read only by the blur"
            ${render} --technique gi.screen --set blur_normal_power=4 --out "${WORK_DIR}/x.exr")
expect_note("" ${render} --technique gi.screen --set blur_normal_power=4 --set blur_radius=1 --out "${WORK_DIR}/x.exr")
expect_note("note: gi.screen ignores --set shadow_resolution=64: read only with shadows=1"
            ${render} --technique gi.screen --set shadows=0 --set shadow_resolution=64 --out "${WORK_DIR}/x.exr")
expect_note("note: compose ignores --set gamma=2: read only with srgb=0"
            ${render} --technique compose --set gamma=2 --out "${WORK_DIR}/x.png")
expect_note("note: compose ignores --set ambient=0.1: the physical formula replaces the ambient term"
            ${render} --technique compose --set formula=physical --set ambient=0.1 --out "${WORK_DIR}/x.png")
expect_note("" ${render} --technique compose --set formula=physical --set ambient=0.1 --set gi=0 --out "${WORK_DIR}/x.png")
# The standard formula (the default) adds the AO-shaded ambient term beside the indirect light.
expect_note("" ${render} --technique compose --set ambient=0.1 --out "${WORK_DIR}/x.png")
# shadow.cube takes every filter's keys, and names those the filter it runs does not read.
set(cube "${OBSCURA}" render --scene cornell_sphere --size 8x8 --frames 1 --technique shadow.cube)
expect_note("note: shadow.cube ignores --set pcf_radius=2: not read with filter=hard"
            ${cube} --set pcf_radius=2 --out "${WORK_DIR}/x.exr")
expect_note("" ${cube} --set pcf_radius=2 --set filter=pcf --out "${WORK_DIR}/x.exr")
expect_note("note: shadow.cube ignores --set contact_steps=8: read only with contact_length > 0"
            ${cube} --set contact_steps=8 --out "${WORK_DIR}/x.exr")
# bench notes a variant once per preset it has no effect in: refine_threshold at full
# resolution (medium), not at half (medium_half).
execute_process(COMMAND "${OBSCURA}" bench --scene cornell --size 8x8 --frames 20 --spp 4 --techniques ao.points
                        --presets medium,medium_half --set bent_normals=0 --variant refine_threshold=0
                        --out "${WORK_DIR}/bench_note" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCHALL "note: [^\n]*" notes "${out}")
if(NOT rc EQUAL 0 OR NOT notes STREQUAL
   "note: preset medium: ao.points ignores --set refine_threshold=0: read only at resolution half or quarter")
  message(FATAL_ERROR "bench --variant refine_threshold=0: expected one note, for preset medium: ${notes}\n${out}${err}")
endif()

# Notes the settings alone cannot decide. The G-buffer computes no direct light to shadow.
expect_note("note: gbuffer ignores --set shadow_resolution=64: read only with direct_lighting=1"
            ${render} --technique gbuffer --set direct_lighting=0 --set shadow_resolution=64 --out "${WORK_DIR}/x.exr")
expect_note("" ${render} --technique gbuffer --set shadow_resolution=64 --out "${WORK_DIR}/x.exr")
# The standard and physical combines multiply AO into the ambient term only (0 by default), so
# ao and radius do nothing until ambient > 0 or under the thesis's formula, which darkens the
# direct light with AO too.
expect_note("note: compose ignores --set ao=1: the standard and physical formulas darken only the ambient term"
            ${render} --technique compose --set gi=0 --set ao=1 --out "${WORK_DIR}/x.png")
expect_note("note: compose ignores --set radius=0.5: read only with gi=1, or with ao=1 where the combine reads AO"
            ${render} --technique compose --set gi=0 --set radius=0.5 --out "${WORK_DIR}/x.png")
expect_note("note: compose ignores --set ao=0: the standard and physical formulas darken only the ambient term"
            ${render} --technique compose --set gi=0 --set ao=0 --out "${WORK_DIR}/x.png")
expect_note("" ${render} --technique compose --set gi=0 --set ao=1 --set radius=0.5 --set ambient=0.2 --out "${WORK_DIR}/x.png")
expect_note("" ${render} --technique compose --set gi=0 --set ao=1 --set radius=0.5 --set formula=thesis --out "${WORK_DIR}/x.png")
# ... and runs the AO pass only where the combine uses it.
foreach(case "gi=0;0" "gi=0;ambient=0.2;1" "gi=0;formula=thesis;1" "formula=thesis;1" "ambient=0.2;1"
             "formula=physical;ambient=0.2;0")
  list(POP_BACK case expected)
  list(TRANSFORM case PREPEND "--set;")
  execute_process(COMMAND ${render} --technique compose ${case} --out "${WORK_DIR}/x.png"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(out MATCHES "compose +ao\\.")
    set(ran 1)
  else()
    set(ran 0)
  endif()
  if(NOT rc EQUAL 0 OR NOT ran EQUAL expected)
    message(FATAL_ERROR "compose ${case}: AO pass ran: ${ran}, expected ${expected}\n${out}${err}")
  endif()
endforeach()
# What the scene decides: cascades with only a spot light, the shadow maps' keys with no
# shadow-casting light. The same floor lit three ways.
function(write_lit_floor name lights)
  file(WRITE "${WORK_DIR}/${name}.json" "{\"meshes\": [{\"positions\": [-1,0,-1, -1,0,1, 1,0,1, 1,0,-1], \"indices\": [0,1,2, 0,2,3]},
  {\"positions\": [-0.2,0.5,-0.2, -0.2,0.5,0.2, 0.2,0.5,0.2, 0.2,0.5,-0.2], \"indices\": [0,1,2, 0,2,3]}],
  \"lights\": [${lights}], \"camera\": {\"eye\": [0,2,3], \"target\": [0,0,0], \"fovy_deg\": 50, \"near\": 0.05, \"far\": 20}}")
endfunction()
set(spot "{\"type\": \"spot\", \"position\": [0,3,0], \"direction\": [0,-1,0], \"intensity\": 10, \"inner_deg\": 20, \"outer_deg\": 30}")
write_lit_floor(spot "${spot}")
write_lit_floor(spot_sun "${spot}, {\"type\": \"directional\", \"direction\": [0,-1,0], \"intensity\": 3}")
write_lit_floor(unshadowed "{\"type\": \"point\", \"position\": [0,3,0], \"intensity\": 10, \"casts_shadows\": false}")
set(floor_render "${OBSCURA}" render --size 8x8 --frames 1)
foreach(key cascades=2 split_lambda=0.5 depth_bounds=0 cascade_blend=0.2)
  expect_note("note: shadow.pcf ignores --set ${key}: the scene has no shadow-casting directional light"
              ${floor_render} --scene "${WORK_DIR}/spot.json" --technique shadow.pcf --set ${key} --out "${WORK_DIR}/x.exr")
  expect_note("" ${floor_render} --scene "${WORK_DIR}/spot_sun.json" --technique shadow.pcf --set ${key} --out "${WORK_DIR}/x.exr")
endforeach()
expect_note("" ${floor_render} --scene "${WORK_DIR}/spot.json" --technique shadow.pcf --set reflective=1 --out "${WORK_DIR}/x.exr")
expect_note("note: shadow.pcf ignores --set split_lambda=0.5: read only with cascades > 1"
            ${floor_render} --scene "${WORK_DIR}/spot_sun.json" --technique shadow.pcf --set cascades=1 --set split_lambda=0.5
            --out "${WORK_DIR}/x.exr")
foreach(technique gbuffer gi.screen compose)
  set(out "${WORK_DIR}/x.exr")
  if(technique STREQUAL "compose")
    set(out "${WORK_DIR}/x.png")
  endif()
  expect_note("note: ${technique} ignores --set shadow_filter=hard: the scene has no shadow-casting light"
              ${floor_render} --scene "${WORK_DIR}/unshadowed.json" --technique ${technique} --set shadow_filter=hard --out "${out}")
  expect_note("" ${floor_render} --scene "${WORK_DIR}/spot.json" --technique ${technique} --set shadow_filter=hard --out "${out}")
endforeach()
# gi's shadows=0 adds the unshadowed measurement in bench whatever the scene's lights.
expect_note("" ${floor_render} --scene "${WORK_DIR}/unshadowed.json" --technique gi.screen --set shadows=0 --out "${WORK_DIR}/x.exr")
# One note a key: a key the settings already leave without effect gets no scene note too.
execute_process(COMMAND ${floor_render} --scene "${WORK_DIR}/unshadowed.json" --technique gbuffer --set direct_lighting=0
                        --set shadow_filter=hard --out "${WORK_DIR}/x.exr" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCHALL "note: [^\n]*" notes "${err}")
if(NOT rc EQUAL 0 OR NOT notes STREQUAL
   "note: gbuffer ignores --set shadow_filter=hard: read only with direct_lighting=1 (shadows darken the direct light)")
  message(FATAL_ERROR "direct_lighting=0 shadow_filter=hard without shadow-casting lights: expected one note: ${notes}\n${out}${err}")
endif()
# bench names the scene for such a note.
execute_process(COMMAND "${OBSCURA}" bench --scene "${WORK_DIR}/spot.json" --size 8x8 --frames 20 --spp 4
                        --techniques shadow.pcf --presets medium --set cascades=2 --out "${WORK_DIR}/bench_scene_note"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCHALL "note: [^\n]*" notes "${out}")
if(NOT rc EQUAL 0 OR NOT notes STREQUAL
   "note: preset medium on spot: shadow.pcf ignores --set cascades=2: the scene has no shadow-casting directional light, the only kind with cascades")
  message(FATAL_ERROR "bench --set cascades=2 on a spot light: expected one note naming the scene: ${notes}\n${out}${err}")
endif()
