/* The machine-profile key table and the reading, checking and storing of
 * one value that the YAML loader, --set and Lua share. See profile_keys.h. */
#include "profile_keys.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dialect.h"
#include "fmt.h"
#include "lexnum.h"
#include "slice.h"

/* Choices are stored as an int through the row's offset. */
_Static_assert(sizeof(lam_process) == sizeof(int) && sizeof(lam_first_line) == sizeof(int),
               "choice fields must be int-sized");

#define AT(field) offsetof(lam_profile, field)

/* `units`: the names lam_key_unit_mm knows (in the same order as mm_per) */
static const char *const unit_choices[] = { "mm", "cm", "m", "um", "\xc2\xb5m", "in", "inch", "ft", NULL };
static const double mm_per[] = { 1, 10, 1000, 1e-3, 1e-3, 25.4, 25.4, 304.8 };
static const char *const process_choices[] = { "ladrp", "sls", NULL };         /* lam_process */
static const char *const cut_choices[] = { "floor", "middle", "ceiling", NULL }; /* lam_cut */
static const char *const frame_choices[] = { "model", "machine", NULL };
static const char *const first_line_choices[] = { "edge", "center", NULL };     /* lam_first_line */
static const char *const strategy_choices[] = { "none", "lines", "stripes", "islands", NULL }; /* lam_strategy */
static const char *const order_choices[] = { "meander", "unidirectional", "greedy", NULL };    /* lam_hatch_order */
static const char *const island_order_choices[] = { "sequential", "checker", "random", NULL }; /* lam_island_order */
static const char *const support_choices[] = { "none", "block", "grid", "lines", NULL };         /* lam_support_type */

/* The least hatch distance, stripe width and island size: a millionth of
 * a unit (1 nm in mm), below any scanner's step in any unit lamina knows.
 * Without it `hatch_distance: 1e-9` loads and fails at the first layer
 * with no line of the profile to point at. */
#define LAM_HATCH_MIN 1e-6

/* The hatch and exposure keys of one vector type: at the top level for the
 * core (with defaults), in a section (`upskin.hatch_distance`) for the
 * others, each following the top-level key when not given. */
#define SCAN_AS(sec, T, key, f, ty, fl, l, h, ch, dflt, inst, text)                                          \
    { .name = sec key, .type = ty, .flags = LAM_KEY_PLAN | (fl), .lo = l, .hi = h, .choices = ch,              \
      .def = sec[0] ? NULL : dflt, .follows = sec[0] ? key : NULL, .offset = AT(scan.type[T].f),               \
      .planner = LAM_READ_SLS, .instead = sec[0] ? NULL : inst, .doc = text }
#define SCAN(sec, T, key, f, ty, fl, l, h, ch, dflt, text) SCAN_AS(sec, T, key, f, ty, fl, l, h, ch, dflt, NULL, text)
#define EXPOSURE_ROWS(sec, T, who)                                                                             \
    SCAN(sec, T, "power", exposure.power, LAM_KEY_NUMBER, 0, 0, HUGE_VAL, NULL, "0", who ": laser power"),      \
    SCAN(sec, T, "speed", exposure.speed, LAM_KEY_NUMBER, 0, 0, HUGE_VAL, NULL, "0",                            \
         who ": scan speed, units per second (0: unknown, no exposure time)"),                                \
    SCAN(sec, T, "point_distance", exposure.point_distance, LAM_KEY_NUMBER, 0, 0, HUGE_VAL, NULL, "0",          \
         who ": point exposure: distance between points (0: continuous scanning)"),                           \
    SCAN(sec, T, "exposure_time", exposure.exposure_time, LAM_KEY_NUMBER, 0, 0, HUGE_VAL, NULL, "0",            \
         who ": point exposure: seconds per point")
#define HATCH_ROWS(sec, T, who)                                                                                \
    SCAN(sec, T, "hatch_strategy", strategy, LAM_KEY_CHOICE, 0, 0, 0, strategy_choices, "none",                   \
         who ": hatching: none (contours only), lines, stripes or islands"),                                      \
    SCAN_AS(sec, T, "hatch_distance", distance, LAM_KEY_NUMBER, 0, LAM_HATCH_MIN, HUGE_VAL, NULL, "0.1",          \
         "bead_width", who ": distance between hatch vectors"),                                                   \
    SCAN_AS(sec, T, "hatch_angle", angle, LAM_KEY_NUMBER, 0, -HUGE_VAL, HUGE_VAL, NULL, "0",                      \
         "raster.angle", who ": hatch direction of the first layer, degrees counter-clockwise from u"),           \
    SCAN_AS(sec, T, "layer_angle_increment", angle_increment, LAM_KEY_NUMBER, 0, -HUGE_VAL, HUGE_VAL, NULL, "67", \
         "raster.angle_step", who ": degrees added to the hatch angle per layer"),                                \
    SCAN_AS(sec, T, "hatch_order", order, LAM_KEY_CHOICE, 0, 0, 0, order_choices, "meander",                      \
         "raster.alternate", who ": meander (alternate), unidirectional or greedy (nearest next end)"),           \
    SCAN_AS(sec, T, "min_vector", min_vector, LAM_KEY_NUMBER, 0, 0, HUGE_VAL, NULL, "0",                          \
         "raster.min_deposit", who ": hatch vectors shorter than this are dropped"),                              \
    SCAN(sec, T, "stripe_width", stripe_width, LAM_KEY_NUMBER, 0, LAM_HATCH_MIN, HUGE_VAL, NULL, "10",          \
         who ": stripes: width of a band"),                                                                   \
    SCAN(sec, T, "stripe_overlap", stripe_overlap, LAM_KEY_NUMBER, 0, 0, HUGE_VAL, NULL, "0",                   \
         who ": stripes: how far neighbouring bands overlap"),                                                \
    SCAN(sec, T, "island_size", island_size, LAM_KEY_NUMBER, 0, LAM_HATCH_MIN, HUGE_VAL, NULL, "5",             \
         who ": islands: side of a square"),                                                                  \
    SCAN(sec, T, "island_overlap", island_overlap, LAM_KEY_NUMBER, 0, 0, HUGE_VAL, NULL, "0",                   \
         who ": islands: how far neighbouring squares overlap"),                                              \
    SCAN(sec, T, "island_order", island_order, LAM_KEY_CHOICE, 0, 0, 0, island_order_choices, "sequential",     \
         who ": islands: sequential, checker (even squares first) or random"),                                \
    SCAN(sec, T, "seed", seed, LAM_KEY_INTEGER, 0, 0, 2147483647, NULL, "0",                                    \
         who ": seed of the random island order (the same seed, the same program)"),                          \
    EXPOSURE_ROWS(sec, T, who)

/* The support keys (support.h, docs/supports.md): read by the SLS planner. */
#define SUPPORT_ROW(key, f, ty, l, h, ch, dflt, text)                                                         \
    { .name = key, .type = ty, .flags = LAM_KEY_PLAN, .lo = l, .hi = h, .choices = ch, .def = dflt,           \
      .offset = AT(scan.support.f), .planner = LAM_READ_SLS, .doc = text }
#define SUPPORT_ROWS                                                                                           \
    SUPPORT_ROW("support_type", type, LAM_KEY_CHOICE, 0, 0, support_choices, "none",                           \
                "sls: supports under overhangs: none, block (a grid of walls with its outline), grid (walls "    \
                "both ways) or lines (walls one way)"),                                                        \
    SUPPORT_ROW("support_angle", angle, LAM_KEY_NUMBER, 0, 90, NULL, "45",                                     \
                "sls: the steepest overhang built without support, degrees from the vertical (45: a "          \
                "45-degree chamfer builds; 90: nothing needs support)"),                                       \
    SUPPORT_ROW("support_gap_xy", gap_xy, LAM_KEY_NUMBER, 0, HUGE_VAL, NULL, "0",                              \
                "sls: least distance from a support to the part's walls beside it (beyond the overhang's own " \
                "reach)"),                                                                                     \
    SUPPORT_ROW("support_gap_z", gap_z, LAM_KEY_NUMBER, 0, HUGE_VAL, NULL, "0",                                \
                "sls: supports stop this far below the part (whole layers; no teeth then)"),                   \
    SUPPORT_ROW("support_min_area", min_area, LAM_KEY_NUMBER, 0, HUGE_VAL, NULL, "0",                          \
                "sls: support regions smaller than this are not made (square units)"),                         \
    SUPPORT_ROW("support_spacing", spacing, LAM_KEY_NUMBER, LAM_HATCH_MIN, HUGE_VAL, NULL, "1",                \
                "sls: distance between support walls"),                                                        \
    SUPPORT_ROW("support_height", height, LAM_KEY_NUMBER, 0, HUGE_VAL, NULL, "0",                              \
                "sls: builds stand parts this high on supports above the plate"),                                  \
    SUPPORT_ROW("support_teeth.height", teeth_height, LAM_KEY_NUMBER, 0, HUGE_VAL, NULL, "0",                  \
                "sls: how far the support's walls reach up into the part (0: no teeth)"),                      \
    SUPPORT_ROW("support_teeth.width", teeth_width, LAM_KEY_NUMBER, 0, HUGE_VAL, NULL, "0.5",                  \
                "sls: a tooth's length along its wall"),                                                       \
    SUPPORT_ROW("support_teeth.spacing", teeth_spacing, LAM_KEY_NUMBER, 0, HUGE_VAL, NULL, "1",                \
                "sls: from one tooth to the next along a wall (at most `width`: one unbroken wall)"),          \
    SUPPORT_ROW("support_perforation.width", perf_width, LAM_KEY_NUMBER, 0, HUGE_VAL, NULL, "0",               \
                "sls: side of the square windows cut into the walls to let powder out (0: none)"),             \
    SUPPORT_ROW("support_perforation.spacing", perf_spacing, LAM_KEY_NUMBER, 0, HUGE_VAL, NULL, "2",           \
                "sls: from one window to the next, along a wall and upwards"),                                 \
    EXPOSURE_ROWS("support.", LAM_KIND_SUPPORT, "sls, supports")

#define TEMPLATE(c, key, when)                                                                                 \
    { .name = "dialect." key, .type = LAM_KEY_TEMPLATE, .flags = LAM_KEY_FIXED | LAM_KEY_OPTIONAL, .cmd = c, \
      .offset = AT(dialect.cmd[c]), .doc = when }

const lam_key lam_profile_keys[] = {
    { .name = "name", .type = LAM_KEY_STRING, .flags = LAM_KEY_NEED | LAM_KEY_NONEMPTY | LAM_KEY_FIXED,
      .offset = AT(name), .doc = "the profile's name (use the file's name without `.yaml`)" },
    { .name = "description", .type = LAM_KEY_STRING, .flags = LAM_KEY_OPTIONAL | LAM_KEY_FIXED,
      .offset = AT(description), .doc = "one line for `lamina machines`" },
    { .name = "process", .type = LAM_KEY_CHOICE, .flags = LAM_KEY_NEED | LAM_KEY_FIXED, .choices = process_choices,
      .offset = AT(process), .doc = "raster deposition (LADRP/DED) or contour sintering (SLS/powder bed)" },
    { .name = "units", .type = LAM_KEY_STRING, .flags = LAM_KEY_NONEMPTY | LAM_KEY_FIXED, .def = "mm",
      .choices = unit_choices, .offset = AT(units),
      .doc = "what one model unit is on this machine (for preambles, the scale bar and the gap limit; nothing is "
             "scaled)" },
    { .name = "bead_width", .type = LAM_KEY_NUMBER,
      .flags = LAM_KEY_ABOVE | LAM_KEY_OPTIONAL | LAM_KEY_NEED_LADRP | LAM_KEY_PLAN, .lo = 0, .hi = HUGE_VAL,
      .offset = AT(bead_width), .planner = LAM_READ_LADRP, .instead = "spot_width",
      .doc = "ladrp: deposited line width `d`; scan lines are `d` apart" },
    { .name = "spot_width", .type = LAM_KEY_NUMBER,
      .flags = LAM_KEY_ABOVE | LAM_KEY_OPTIONAL | LAM_KEY_NEED_SLS | LAM_KEY_PLAN, .lo = 0, .hi = HUGE_VAL,
      .offset = AT(spot_width), .planner = LAM_READ_SLS, .instead = "bead_width",
      .doc = "sls: laser spot; an sls profile's bead width is its spot width" },
    { .name = "layer_width", .alias = "layer_thickness", .type = LAM_KEY_NUMBER,
      .flags = LAM_KEY_ABOVE | LAM_KEY_OPTIONAL, .lo = 0, .hi = HUGE_VAL, .option = "width", .letter = 'w', .offset = AT(layer_width),
      .doc = "layer thickness when the command line or recipe gives none (absent: the slicer's default)" },
    { .name = "cut", .type = LAM_KEY_CHOICE, .choices = cut_choices, .def = "middle", .option = "cut",
      .offset = AT(cut), .doc = "where in the layer the section is taken" },
    { .name = "feed_rate", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_PLAN, .lo = 0, .hi = HUGE_VAL, .def = "0",
      .offset = AT(feed_rate), .planner = LAM_READ_LADRP, .instead = "speed",
      .doc = "ladrp: deposit feed rate (the thesis's powder feed `R`)" },
    { .name = "travel_rate", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_PLAN, .lo = 0, .hi = HUGE_VAL,
      .follows = "feed_rate", .offset = AT(travel_rate), .planner = LAM_READ_LADRP, .instead = "jump_speed",
      .doc = "ladrp: rate of moves with the laser off" },
    { .name = "gap", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_AUTO, .lo = 0, .hi = HUGE_VAL, .def = "auto",
      .option = "gap", .offset = AT(gap),
      .doc = "close open outlines whose ends are this close (0: never; auto: 1/2000 of the model's size, at most "
             "0.05 mm in the profile's units)" },
    { .name = "frame", .type = LAM_KEY_CHOICE, .flags = LAM_KEY_PLAN, .choices = frame_choices, .def = "model",
      .option = "frame", .offset = AT(frame_machine),
      .doc = "coordinates written: model x y z, or the layer frame u v w (build axis = machine Z)" },
    { .name = "raster.first_line", .type = LAM_KEY_CHOICE, .flags = LAM_KEY_PLAN | LAM_KEY_FLAT,
      .choices = first_line_choices, .def = "edge", .option = "first-line", .offset = AT(first_line),
      .planner = LAM_READ_LADRP,
      .doc = "ladrp: first scan line on the layer's top edge (the thesis) or half a bead inside" },
    { .name = "raster.angle", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_PLAN | LAM_KEY_FLAT, .lo = -HUGE_VAL,
      .hi = HUGE_VAL, .def = "0", .option = "angle", .offset = AT(angle), .planner = LAM_READ_LADRP,
      .instead = "hatch_angle",
      .doc = "ladrp: raster direction of the first layer, degrees" },
    { .name = "raster.angle_step", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_PLAN | LAM_KEY_FLAT, .lo = -HUGE_VAL,
      .hi = HUGE_VAL, .def = "0", .option = "angle-step", .offset = AT(angle_step), .planner = LAM_READ_LADRP,
      .instead = "layer_angle_increment",
      .doc = "ladrp: degrees added per layer (90: cross-hatch, 67.5: rotating)" },
    { .name = "raster.alternate", .type = LAM_KEY_BOOLEAN, .flags = LAM_KEY_PLAN | LAM_KEY_FLAT, .def = "true",
      .option = "no-alternate", .offset = AT(alternate), .planner = LAM_READ_LADRP, .instead = "hatch_order",
      .doc = "ladrp: boustrophedon, every other line runs backwards" },
    { .name = "raster.min_deposit", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_PLAN | LAM_KEY_FLAT, .lo = 0,
      .hi = HUGE_VAL, .def = "0", .option = "min-deposit", .offset = AT(min_deposit),
      .planner = LAM_READ_LADRP, .instead = "min_vector",
      .doc = "ladrp: deposits shorter than this are skipped" },
    { .name = "raster.perimeters", .type = LAM_KEY_INTEGER, .flags = LAM_KEY_PLAN | LAM_KEY_FLAT, .lo = 0,
      .hi = 1000, .def = "0", .option = "perimeters", .offset = AT(perimeters),
      .planner = LAM_READ_LADRP, .instead = "contour_count",
      .doc = "ladrp: passes around each contour, the first offset by `d/2`" },
    { .name = "raster.islands", .type = LAM_KEY_BOOLEAN, .flags = LAM_KEY_PLAN | LAM_KEY_FLAT, .def = "false",
      .option = "islands", .offset = AT(islands), .planner = LAM_READ_LADRP,
      .instead = "hatch_strategy=islands",
      .doc = "ladrp: raster each island (an outer contour and what it holds) on its own, the nearest next, "
             "instead of whole scan lines across the layer: less travel between islands" },
    { .name = "beam_offset", .type = LAM_KEY_BOOLEAN, .flags = LAM_KEY_PLAN, .def = "false",
      .option = "beam-offset", .offset = AT(beam_offset), .planner = LAM_READ_SLS,
      .doc = "sls: inset contours by half the spot" },
    HATCH_ROWS("", LAM_KIND_CORE, "sls, core"),
    { .name = "contour_count", .type = LAM_KEY_INTEGER, .flags = LAM_KEY_PLAN, .lo = 0, .hi = 1000, .def = "1",
      .offset = AT(scan.contour_count), .planner = LAM_READ_SLS,
      .instead = "raster.perimeters", .doc = "sls: contour passes round the region (the first offset by the spot "
                                                "compensation when `beam_offset`)" },
    { .name = "contour_distance", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_PLAN, .lo = 0, .hi = HUGE_VAL,
      .follows = "spot_width", .offset = AT(scan.contour_distance), .planner = LAM_READ_SLS,
      .doc = "sls: each next contour pass this much further in" },
    { .name = "hatch_offset", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_PLAN, .lo = 0, .hi = HUGE_VAL, .def = "0",
      .offset = AT(scan.hatch_offset), .planner = LAM_READ_SLS,
      .doc = "sls: distance from the innermost contour pass to the hatched area" },
    { .name = "contours_first", .type = LAM_KEY_BOOLEAN, .flags = LAM_KEY_PLAN, .def = "true",
      .offset = AT(scan.contours_first), .planner = LAM_READ_SLS,
      .doc = "sls: contour passes before the hatches (false: after)" },
    { .name = "skin_layers", .type = LAM_KEY_INTEGER, .flags = LAM_KEY_PLAN, .lo = 0, .hi = LAM_SKIN_MAX, .def = "0",
      .offset = AT(scan.skin_layers), .planner = LAM_READ_SLS,
      .doc = "sls: how many layers deep up-skin and down-skin reach (0: no skins, all core)" },
    { .name = "jump_speed", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_PLAN, .lo = 0, .hi = HUGE_VAL, .def = "0",
      .offset = AT(scan.jump_speed), .planner = LAM_READ_SLS,
      .doc = "sls: scanner speed between vectors, units per second (0: jumps take "
                                             "only their delay)" },
    { .name = "jump_delay", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_PLAN, .lo = 0, .hi = HUGE_VAL, .def = "0",
      .offset = AT(scan.jump_delay), .planner = LAM_READ_SLS, .doc = "sls: seconds added to every jump" },
    { .name = "recoat_time", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_PLAN, .lo = 0, .hi = HUGE_VAL, .def = "0",
      .offset = AT(scan.recoat_time), .planner = LAM_READ_SLS, .doc = "sls: seconds to spread each layer's powder" },
    EXPOSURE_ROWS("contour.", LAM_KIND_CONTOUR, "sls, contour passes"),
    HATCH_ROWS("upskin.", LAM_KIND_UPSKIN, "sls, up-skin"),
    HATCH_ROWS("downskin.", LAM_KIND_DOWNSKIN, "sls, down-skin"),
    SUPPORT_ROWS,
    { .name = "plate.width", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_ABOVE | LAM_KEY_OPTIONAL, .lo = 0,
      .hi = HUGE_VAL, .offset = AT(plate_width),
      .doc = "builds: a rectangular build plate's width (x); plate coordinates start at its front-left corner (with "
             "`plate.depth`)" },
    { .name = "plate.depth", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_ABOVE | LAM_KEY_OPTIONAL, .lo = 0,
      .hi = HUGE_VAL, .offset = AT(plate_depth),
      .doc = "builds: a rectangular build plate's depth (y) (with `plate.width`)" },
    { .name = "plate.diameter", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_ABOVE | LAM_KEY_OPTIONAL, .lo = 0,
      .hi = HUGE_VAL, .offset = AT(plate_diameter),
      .doc = "builds: a round build plate's diameter, instead of `plate.width` and `plate.depth`; plate "
             "coordinates start at its centre" },
    { .name = "plate.margin", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_OPTIONAL, .lo = 0, .hi = HUGE_VAL,
      .def = "0", .offset = AT(plate_margin), .doc = "builds: kept free of parts along the plate's edge" },
    { .name = "spacing", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_OPTIONAL, .lo = 0, .hi = HUGE_VAL, .def = "0",
      .offset = AT(spacing), .doc = "builds: least distance between two parts' footprints on the plate" },
    { .name = "gas_flow", .type = LAM_KEY_NUMBERS, .flags = LAM_KEY_OPTIONAL, .lo = -HUGE_VAL, .hi = HUGE_VAL,
      .count = 2, .offset = AT(gas_flow),
      .doc = "builds: `[dx, dy]`, the direction the shielding gas flows in over the plate (`[-1, 0]`: from +x "
             "towards -x; absent or `[0, 0]`: none)" },
    { .name = "lasers", .type = LAM_KEY_LASERS, .flags = LAM_KEY_OPTIONAL, .offset = AT(nlasers),
      .doc = "builds: `[{field: [x0, y0, x1, y1]}, ...]`, each laser's field: the box of the plate it reaches, "
             "in plate coordinates (absent: none given)" },
    { .name = "max_overhang_deg", .type = LAM_KEY_NUMBER, .flags = LAM_KEY_OPTIONAL, .lo = 0, .hi = 90,
      .offset = AT(max_overhang_deg), .doc = "design rule for `lamina check`, degrees from the vertical (0: no rule)" },
    { .name = "writer", .type = LAM_KEY_STRING, .flags = LAM_KEY_NONEMPTY | LAM_KEY_FIXED, .def = "text",
      .offset = AT(writer),
      .doc = "`text` writes the dialect; another name selects a plugin writer (e.g. binary CLI)" },
    { .name = "inherits", .type = LAM_KEY_STRING, .flags = LAM_KEY_NONEMPTY | LAM_KEY_FIXED | LAM_KEY_LOADER,
      .doc = "a profile to start from: a name (machine directories) or a path" },
    { .name = "dialect.close_polylines", .type = LAM_KEY_BOOLEAN, .flags = LAM_KEY_FIXED, .def = "false",
      .offset = AT(dialect.close_polylines), .doc = "repeat each contour's first point at its end" },
    TEMPLATE(LAM_CMD_PREAMBLE, "preamble", "once, first"),
    TEMPLATE(LAM_CMD_POSTAMBLE, "postamble", "once, last"),
    TEMPLATE(LAM_CMD_LAYER, "layer", "at the start of each layer"),
    TEMPLATE(LAM_CMD_LAYER_END, "layer_end", "at the end of each layer"),
    TEMPLATE(LAM_CMD_FEED, "feed", "the planner sets the feed rate"),
    TEMPLATE(LAM_CMD_LASER_ON, "laser_on", "the laser switches on (`rate`: the deposit rate)"),
    TEMPLATE(LAM_CMD_LASER_OFF, "laser_off", "the laser switches off (`rate`: the deposit rate)"),
    TEMPLATE(LAM_CMD_TRAVEL, "travel", "a move with the laser off (`rate`: `travel_rate`)"),
    TEMPLATE(LAM_CMD_DEPOSIT, "deposit", "a move with the laser on (`rate`: `feed_rate`)"),
    TEMPLATE(LAM_CMD_CONTOUR_BEGIN, "contour_begin", "a contour starts"),
    TEMPLATE(LAM_CMD_CONTOUR_END, "contour_end", "after `loop_end`"),
    TEMPLATE(LAM_CMD_LOOP_BEGIN, "loop_begin", "after `contour_begin`"),
    TEMPLATE(LAM_CMD_LOOP_END, "loop_end", "after the points"),
    TEMPLATE(LAM_CMD_VERTEX, "vertex", "each point of the contour"),
    TEMPLATE(LAM_CMD_POLYLINE, "polyline", "after `contour_end`: the whole contour as one line"),
    TEMPLATE(LAM_CMD_SEPARATOR, "separator", "between two contour or hatch blocks (not before the first)"),
    TEMPLATE(LAM_CMD_HATCHES_BEGIN, "hatches_begin", "a block of hatch vectors starts (a region, stripe or island)"),
    TEMPLATE(LAM_CMD_HATCH, "hatch", "each hatch vector of the block"),
    TEMPLATE(LAM_CMD_HATCHES_END, "hatches_end", "after the block's vectors"),
    TEMPLATE(LAM_CMD_HATCHES, "hatches", "after `hatches_end`: the whole block as one line"),
};

const size_t lam_profile_nkeys = sizeof lam_profile_keys / sizeof lam_profile_keys[0];
_Static_assert(sizeof lam_profile_keys / sizeof lam_profile_keys[0] <= LAM_KEYS_MAX, "raise LAM_KEYS_MAX");

/* ---- names ---------------------------------------------------------------- */

size_t lam_key_section_len(const lam_key *k)
{
    const char *dot = strchr(k->name, '.');
    return dot ? (size_t)(dot - k->name) : 0;
}

const char *lam_key_short(const lam_key *k)
{
    size_t n = lam_key_section_len(k);
    return n ? k->name + n + 1 : k->name;
}

const char *lam_key_lua_name(const lam_key *k)
{
    return k->flags & LAM_KEY_FLAT ? lam_key_short(k) : k->name;
}

const lam_key *lam_key_find(const char *name)
{
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        if (!strcmp(k->name, name) || (k->alias && !strcmp(k->alias, name))) return k;
    }
    for (size_t i = 0; i < lam_profile_nkeys; i++)
        if (lam_profile_keys[i].flags & LAM_KEY_FLAT && !strcmp(lam_key_short(&lam_profile_keys[i]), name))
            return &lam_profile_keys[i];
    return NULL;
}

const lam_key *lam_key_at(size_t offset)
{
    for (size_t i = 0; i < lam_profile_nkeys; i++)
        if (!(lam_profile_keys[i].flags & LAM_KEY_LOADER) && lam_profile_keys[i].offset == offset)
            return &lam_profile_keys[i];
    return NULL;
}

/* ---- who reads a key -------------------------------------------------------- */

static const char *process_name(int process)
{
    return process_choices[process == LAM_PROCESS_SLS];
}

int lam_key_read_by(const lam_key *k, int process)
{
    if (k->planner == LAM_READ_LADRP) return process == LAM_PROCESS_LADRP;
    if (k->planner == LAM_READ_SLS) return process == LAM_PROCESS_SLS;
    return 1;
}

int lam_key_unread(const lam_key *k, const char *as, int process, const char *profile, lam_error *err)
{
    const char *name = as ? as : k->name;
    const char *reader = process_name(process == LAM_PROCESS_SLS ? LAM_PROCESS_LADRP : LAM_PROCESS_SLS);
    char other[160] = "no key does the same";
    if (k->instead) {
        /* the other key's own option, when it has one (raster.angle: --angle) */
        char key[64];
        snprintf(key, sizeof key, "%.*s", (int)strcspn(k->instead, "="), k->instead);
        const lam_key *o = lam_key_find(key);
        char opt[48] = "";
        if (o && o->option) snprintf(opt, sizeof opt, " (--%s)", o->option);
        snprintf(other, sizeof other, "set %s instead%s", k->instead, opt);
    }
    return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s is read by the %s planner only, and %s is %s %s profile: %s",
                         name, reader, profile ? profile : "this", process == LAM_PROCESS_SLS ? "an" : "a",
                         process_name(process), other);
}

/* ---- units ------------------------------------------------------------------- */

_Static_assert(sizeof unit_choices / sizeof unit_choices[0] == sizeof mm_per / sizeof mm_per[0] + 1,
               "a factor for every unit name");

double lam_key_unit_mm(const char *units)
{
    for (size_t i = 0; units && unit_choices[i]; i++)
        if (!strcmp(units, unit_choices[i])) return mm_per[i];
    return 0;
}

/* ---- names, continued ---------------------------------------------------------- */

static size_t distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 40 || lb > 40) return 99;
    size_t row[41];
    for (size_t j = 0; j <= lb; j++) row[j] = j;
    for (size_t i = 1; i <= la; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= lb; j++) {
            size_t up = row[j];
            size_t best = diag + (a[i - 1] != b[j - 1]);
            if (up + 1 < best) best = up + 1;
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[lb];
}

const char *lam_key_nearest(const char *word, const char *const *names, size_t n)
{
    const char *best = NULL;
    size_t bd = 3;
    for (size_t j = 0; j < n; j++) {
        size_t d = distance(word, names[j]);
        if (d < bd) bd = d, best = names[j];
    }
    return best;
}

/* ---- one value ------------------------------------------------------------ */

static const char *num(char *buf, double x)
{
    lam_dialect_number(buf, x);
    return buf;
}

int lam_key_check(const lam_key *k, const char *as, double x, const char *shown, lam_error *err)
{
    const char *name = as ? as : k->name;
    char lo[LAM_FMT_MAX], hi[LAM_FMT_MAX];
    num(lo, k->lo);
    num(hi, k->hi);
    if (k->type == LAM_KEY_INTEGER) {
        if (x != floor(x) || x < k->lo || x > k->hi)
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s must be a whole number from %s to %s, got %s", name,
                                 lo, hi, shown);
        return LAM_OK;
    }
    if (k->type != LAM_KEY_NUMBER && k->type != LAM_KEY_NUMBERS) return LAM_OK;
    int above = k->flags & LAM_KEY_ABOVE;
    if ((above ? x > k->lo : x >= k->lo) && x <= k->hi) return LAM_OK;
    if (k->hi == HUGE_VAL)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s must be %s%s%s, got %s", name,
                             above ? "greater than " : "", lo, above ? "" : " or more", shown);
    if (above)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s must be greater than %s and at most %s, got %s", name,
                             lo, hi, shown);
    return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s must be from %s to %s, got %s", name, lo, hi, shown);
}

/* "a, b or c" */
static void choice_list(const lam_key *k, char *out, size_t size)
{
    if (!k->choices) {
        snprintf(out, size, "text");
        return;
    }
    size_t n = 0;
    out[0] = '\0';
    for (int i = 0; k->choices[i] && n + 1 < size; i++) {
        int w = snprintf(out + n, size - n, "%s%s", i ? (k->choices[i + 1] ? ", " : " or ") : "", k->choices[i]);
        if (w < 0) break;
        n += (size_t)w;
    }
}

static int word_is(const char *text, size_t len, const char *w)
{
    return strlen(w) == len && !memcmp(text, w, len);
}

int lam_key_expected(const lam_key *k, const char *as, const char *got, lam_error *err)
{
    char list[200];
    const char *what = list;
    switch (k->type) {
    case LAM_KEY_NUMBER:
    case LAM_KEY_INTEGER: what = k->flags & LAM_KEY_AUTO ? "a number or auto" : "a number"; break;
    case LAM_KEY_BOOLEAN: what = "true or false"; break;
    case LAM_KEY_CHOICE: choice_list(k, list, sizeof list); break;
    case LAM_KEY_STRING: choice_list(k, list, sizeof list); break;
    case LAM_KEY_TEMPLATE: what = "a template (text) or null"; break;
    case LAM_KEY_NUMBERS: snprintf(list, sizeof list, "a list of %zu numbers", k->count); break;
    case LAM_KEY_LASERS:
        snprintf(list, sizeof list, "a list of 1 to %d lasers ({field: [x0, y0, x1, y1]})", LAM_PROFILE_LASERS_MAX);
        break;
    }
    return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s must be %s, got %s", as ? as : k->name, what, got);
}

int lam_key_scan(const lam_key *k, const char *as, const char *text, size_t len, double *x, lam_error *err)
{
    static const char *const yes[] = { "true", "True", "TRUE", "yes", "Yes", "YES", NULL };
    static const char *const no[] = { "false", "False", "FALSE", "no", "No", "NO", NULL };
    char shown[64];
    lam_quote_bytes(shown, sizeof shown, (const unsigned char *)text, len);
    double v;
    switch (k->type) {
    case LAM_KEY_NUMBER:
    case LAM_KEY_INTEGER: {
        if (k->flags & LAM_KEY_AUTO && word_is(text, len, "auto")) return *x = -1, LAM_OK;
        int rc = lam_parse_number((const unsigned char *)text, len, &v);
        if (rc == LAM_ENOMEM) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory");
        if (rc) return lam_key_expected(k, as, shown, err);
        if (!isfinite(v))
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s must be a finite number, got %s", as ? as : k->name,
                                 shown);
        if ((rc = lam_key_check(k, as, v, shown, err))) return rc;
        *x = v;
        return LAM_OK;
    }
    case LAM_KEY_BOOLEAN:
        for (int i = 0; yes[i]; i++)
            if (word_is(text, len, yes[i])) return *x = 1, LAM_OK;
        for (int i = 0; no[i]; i++)
            if (word_is(text, len, no[i])) return *x = 0, LAM_OK;
        return lam_key_expected(k, as, shown, err);
    case LAM_KEY_CHOICE:
        for (int i = 0; k->choices[i]; i++)
            if (word_is(text, len, k->choices[i])) return *x = i, LAM_OK;
        return lam_key_expected(k, as, shown, err);
    default:
        return lam_key_expected(k, as, shown, err);
    }
}

int lam_key_check_text(const lam_key *k, const char *text, lam_error *err)
{
    if (k->flags & LAM_KEY_NONEMPTY && !*text)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s must not be empty", k->name);
    if (!k->choices) return LAM_OK;
    for (size_t i = 0; k->choices[i]; i++)
        if (!strcmp(text, k->choices[i])) return LAM_OK;
    char shown[64];
    lam_quote_bytes(shown, sizeof shown, (const unsigned char *)text, strlen(text));
    return lam_key_expected(k, NULL, shown, err);
}

double lam_key_get(const lam_profile *p, const lam_key *k)
{
    const char *at = (const char *)p + k->offset;
    if (k->type == LAM_KEY_NUMBER) return *(const double *)(const void *)at;
    if (k->type == LAM_KEY_INTEGER || k->type == LAM_KEY_BOOLEAN || k->type == LAM_KEY_CHOICE)
        return *(const int *)(const void *)at;
    return 0;
}

void lam_key_store(lam_profile *p, const lam_key *k, double x)
{
    char *at = (char *)p + k->offset;
    if (k->type == LAM_KEY_NUMBER) *(double *)(void *)at = x;
    else if (k->type == LAM_KEY_INTEGER || k->type == LAM_KEY_BOOLEAN || k->type == LAM_KEY_CHOICE)
        *(int *)(void *)at = (int)x;
}

void lam_key_put(lam_profile *p, const lam_key *k, double x)
{
    double old = lam_key_get(p, k);
    lam_key_store(p, k, x);
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *f = &lam_profile_keys[i];
        if (f->follows && !strcmp(f->follows, k->name) && lam_key_get(p, f) == old) lam_key_store(p, f, x);
    }
    /* one plate shape: a round plate or a rectangular one */
    if (k->offset == AT(plate_diameter) && x > 0) p->plate_width = p->plate_depth = 0;
    if ((k->offset == AT(plate_width) || k->offset == AT(plate_depth)) && x > 0) p->plate_diameter = 0;
    /* one width for sls: whichever of the two is set */
    if (p->process == LAM_PROCESS_SLS) {
        if (k->offset == AT(bead_width)) p->spot_width = x;
        if (k->offset == AT(spot_width)) p->bead_width = x;
    }
}

int lam_key_given(const lam_profile *p, const lam_key *k)
{
    const char *at = (const char *)p + k->offset;
    if (!(k->flags & LAM_KEY_OPTIONAL)) return 1;
    switch (k->type) {
    case LAM_KEY_TEMPLATE: return ((const lam_template *)(const void *)at)->present;
    case LAM_KEY_STRING: return *(char *const *)(const void *)at != NULL;
    case LAM_KEY_LASERS: return p->nlasers > 0;
    case LAM_KEY_NUMBERS:
        for (size_t i = 0; i < k->count; i++)
            if (((const double *)(const void *)at)[i] != 0) return 1;
        return 0;
    default: return lam_key_get(p, k) != 0;
    }
}

/* "[a, b, c]" of v[0..n) into buf (LAM_FMT_MAX per number) */
static const char *num_list(char *buf, size_t size, const double *v, size_t n)
{
    size_t len = 0;
    buf[len++] = '[';
    for (size_t i = 0; i < n && len + LAM_FMT_MAX + 3 < size; i++) {
        if (i) buf[len++] = ',', buf[len++] = ' ';
        len += lam_dialect_number(buf + len, v[i]);
    }
    buf[len++] = ']';
    buf[len] = '\0';
    return buf;
}

int lam_key_check_numbers(const lam_key *k, const char *as, const double *v, size_t n, lam_error *err)
{
    const char *name = as ? as : k->name;
    if (n != k->count)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s must be a list of %zu numbers, got a list of %zu", name,
                             k->count, n);
    for (size_t i = 0; i < n; i++) {
        char shown[LAM_FMT_MAX];
        if (!isfinite(v[i]))
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s must be finite numbers, got %s", name,
                                 isnan(v[i]) ? "nan" : v[i] > 0 ? "inf" : "-inf");
        int rc = lam_key_check(k, as, v[i], num(shown, v[i]), err);
        if (rc) return rc;
    }
    return LAM_OK;
}

int lam_key_check_field(const double f[4], lam_error *err)
{
    char shown[4 * LAM_FMT_MAX + 16];
    for (int i = 0; i < 4; i++)
        if (!isfinite(f[i]))
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "a laser's field must be 4 finite numbers [x0, y0, x1, y1]");
    if (f[0] < f[2] && f[1] < f[3]) return LAM_OK;
    return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "a laser's field must have x0 < x1 and y0 < y1, got %s",
                         num_list(shown, sizeof shown, f, 4));
}

int lam_profile_check_plate(const lam_profile *p, lam_error *err)
{
    if (p->plate_diameter > 0 && (p->plate_width > 0 || p->plate_depth > 0))
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                             "plate.diameter excludes plate.width and plate.depth (a plate is round or rectangular)");
    if ((p->plate_width > 0) != (p->plate_depth > 0))
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                             "plate.width and plate.depth go together: give both (a rectangular plate) or "
                             "plate.diameter (a round one)");
    return LAM_OK;
}

/* ---- after --set ---------------------------------------------------------- */

int lam_profile_check(const lam_profile *p, lam_error *err)
{
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        unsigned need = p->process == LAM_PROCESS_SLS ? LAM_KEY_NEED_SLS : LAM_KEY_NEED_LADRP;
        if (k->flags & need && !(lam_key_get(p, k) > 0))
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "%s must be given for process %s", k->name,
                                 process_choices[p->process == LAM_PROCESS_SLS]);
    }
    return lam_profile_check_plate(p, err);
}
