//! The Utah teapot, the mesh that ships with obscura (`host/scenes/teapot.obj`, drawn by
//! `host/scenes/teapot.toml`): this module owns Martin Newell's data for it, 32 bicubic Bézier
//! patches over 306 control points, its tessellation into a triangle mesh ([`teapot`]) and the
//! mesh written as Wavefront OBJ ([`Teapot::obj_text`], through [`obscura_scene::obj_text`]). The
//! shipped file is generated here, never edited: a test checks that it is what
//! [`Teapot::obj_text`] makes of [`SHIPPED_STEPS`].

use obscura_scene::CornerNormals;
use std::collections::HashMap;

/// The steps per patch of the teapot that ships with obscura (`host/scenes/teapot.obj`): 3,
/// a few hundred triangles (552, on 301 vertices).
pub const SHIPPED_STEPS: u16 = 3;

/// The most steps per patch [`teapot`] takes: 32·8001² vertices still have `u32` indices.
const MOST_STEPS: usize = 8000;

/// The Newell teapot's control points (x, y, z with z up, as Newell gave them).
const POINTS: [[f32; 3]; 306] = [
    // 0–47: the rim, whose outer edge is the body's top edge.
    [1.4, 0.0, 2.4],
    [1.4, -0.784, 2.4],
    [0.784, -1.4, 2.4],
    [0.0, -1.4, 2.4],
    [1.3375, 0.0, 2.53125],
    [1.3375, -0.749, 2.53125],
    [0.749, -1.3375, 2.53125],
    [0.0, -1.3375, 2.53125],
    [1.4375, 0.0, 2.53125],
    [1.4375, -0.805, 2.53125],
    [0.805, -1.4375, 2.53125],
    [0.0, -1.4375, 2.53125],
    [1.5, 0.0, 2.4],
    [1.5, -0.84, 2.4],
    [0.84, -1.5, 2.4],
    [0.0, -1.5, 2.4],
    [-0.784, -1.4, 2.4],
    [-1.4, -0.784, 2.4],
    [-1.4, 0.0, 2.4],
    [-0.749, -1.3375, 2.53125],
    [-1.3375, -0.749, 2.53125],
    [-1.3375, 0.0, 2.53125],
    [-0.805, -1.4375, 2.53125],
    [-1.4375, -0.805, 2.53125],
    [-1.4375, 0.0, 2.53125],
    [-0.84, -1.5, 2.4],
    [-1.5, -0.84, 2.4],
    [-1.5, 0.0, 2.4],
    [-1.4, 0.784, 2.4],
    [-0.784, 1.4, 2.4],
    [0.0, 1.4, 2.4],
    [-1.3375, 0.749, 2.53125],
    [-0.749, 1.3375, 2.53125],
    [0.0, 1.3375, 2.53125],
    [-1.4375, 0.805, 2.53125],
    [-0.805, 1.4375, 2.53125],
    [0.0, 1.4375, 2.53125],
    [-1.5, 0.84, 2.4],
    [-0.84, 1.5, 2.4],
    [0.0, 1.5, 2.4],
    [0.784, 1.4, 2.4],
    [1.4, 0.784, 2.4],
    [0.749, 1.3375, 2.53125],
    [1.3375, 0.749, 2.53125],
    [0.805, 1.4375, 2.53125],
    [1.4375, 0.805, 2.53125],
    [0.84, 1.5, 2.4],
    [1.5, 0.84, 2.4],
    // 48–119: the body.
    [1.75, 0.0, 1.875],
    [1.75, -0.98, 1.875],
    [0.98, -1.75, 1.875],
    [0.0, -1.75, 1.875],
    [2.0, 0.0, 1.35],
    [2.0, -1.12, 1.35],
    [1.12, -2.0, 1.35],
    [0.0, -2.0, 1.35],
    [2.0, 0.0, 0.9],
    [2.0, -1.12, 0.9],
    [1.12, -2.0, 0.9],
    [0.0, -2.0, 0.9],
    [-0.98, -1.75, 1.875],
    [-1.75, -0.98, 1.875],
    [-1.75, 0.0, 1.875],
    [-1.12, -2.0, 1.35],
    [-2.0, -1.12, 1.35],
    [-2.0, 0.0, 1.35],
    [-1.12, -2.0, 0.9],
    [-2.0, -1.12, 0.9],
    [-2.0, 0.0, 0.9],
    [-1.75, 0.98, 1.875],
    [-0.98, 1.75, 1.875],
    [0.0, 1.75, 1.875],
    [-2.0, 1.12, 1.35],
    [-1.12, 2.0, 1.35],
    [0.0, 2.0, 1.35],
    [-2.0, 1.12, 0.9],
    [-1.12, 2.0, 0.9],
    [0.0, 2.0, 0.9],
    [0.98, 1.75, 1.875],
    [1.75, 0.98, 1.875],
    [1.12, 2.0, 1.35],
    [2.0, 1.12, 1.35],
    [1.12, 2.0, 0.9],
    [2.0, 1.12, 0.9],
    [2.0, 0.0, 0.45],
    [2.0, -1.12, 0.45],
    [1.12, -2.0, 0.45],
    [0.0, -2.0, 0.45],
    [1.5, 0.0, 0.225],
    [1.5, -0.84, 0.225],
    [0.84, -1.5, 0.225],
    [0.0, -1.5, 0.225],
    [1.5, 0.0, 0.15],
    [1.5, -0.84, 0.15],
    [0.84, -1.5, 0.15],
    [0.0, -1.5, 0.15],
    [-1.12, -2.0, 0.45],
    [-2.0, -1.12, 0.45],
    [-2.0, 0.0, 0.45],
    [-0.84, -1.5, 0.225],
    [-1.5, -0.84, 0.225],
    [-1.5, 0.0, 0.225],
    [-0.84, -1.5, 0.15],
    [-1.5, -0.84, 0.15],
    [-1.5, 0.0, 0.15],
    [-2.0, 1.12, 0.45],
    [-1.12, 2.0, 0.45],
    [0.0, 2.0, 0.45],
    [-1.5, 0.84, 0.225],
    [-0.84, 1.5, 0.225],
    [0.0, 1.5, 0.225],
    [-1.5, 0.84, 0.15],
    [-0.84, 1.5, 0.15],
    [0.0, 1.5, 0.15],
    [1.12, 2.0, 0.45],
    [2.0, 1.12, 0.45],
    [0.84, 1.5, 0.225],
    [1.5, 0.84, 0.225],
    [0.84, 1.5, 0.15],
    [1.5, 0.84, 0.15],
    // 120–160: the handle.
    [-1.6, 0.0, 2.025],
    [-1.6, -0.3, 2.025],
    [-1.5, -0.3, 2.25],
    [-1.5, 0.0, 2.25],
    [-2.3, 0.0, 2.025],
    [-2.3, -0.3, 2.025],
    [-2.5, -0.3, 2.25],
    [-2.5, 0.0, 2.25],
    [-2.7, 0.0, 2.025],
    [-2.7, -0.3, 2.025],
    [-3.0, -0.3, 2.25],
    [-3.0, 0.0, 2.25],
    [-2.7, 0.0, 1.8],
    [-2.7, -0.3, 1.8],
    [-3.0, -0.3, 1.8],
    [-3.0, 0.0, 1.8],
    [-1.5, 0.3, 2.25],
    [-1.6, 0.3, 2.025],
    [-2.5, 0.3, 2.25],
    [-2.3, 0.3, 2.025],
    [-3.0, 0.3, 2.25],
    [-2.7, 0.3, 2.025],
    [-3.0, 0.3, 1.8],
    [-2.7, 0.3, 1.8],
    [-2.7, 0.0, 1.575],
    [-2.7, -0.3, 1.575],
    [-3.0, -0.3, 1.35],
    [-3.0, 0.0, 1.35],
    [-2.5, 0.0, 1.125],
    [-2.5, -0.3, 1.125],
    [-2.65, -0.3, 0.9375],
    [-2.65, 0.0, 0.9375],
    [-2.0, -0.3, 0.9],
    [-1.9, -0.3, 0.6],
    [-1.9, 0.0, 0.6],
    [-3.0, 0.3, 1.35],
    [-2.7, 0.3, 1.575],
    [-2.65, 0.3, 0.9375],
    [-2.5, 0.3, 1.125],
    [-1.9, 0.3, 0.6],
    [-2.0, 0.3, 0.9],
    // 161–202: the spout.
    [1.7, 0.0, 1.425],
    [1.7, -0.66, 1.425],
    [1.7, -0.66, 0.6],
    [1.7, 0.0, 0.6],
    [2.6, 0.0, 1.425],
    [2.6, -0.66, 1.425],
    [3.1, -0.66, 0.825],
    [3.1, 0.0, 0.825],
    [2.3, 0.0, 2.1],
    [2.3, -0.25, 2.1],
    [2.4, -0.25, 2.025],
    [2.4, 0.0, 2.025],
    [2.7, 0.0, 2.4],
    [2.7, -0.25, 2.4],
    [3.3, -0.25, 2.4],
    [3.3, 0.0, 2.4],
    [1.7, 0.66, 0.6],
    [1.7, 0.66, 1.425],
    [3.1, 0.66, 0.825],
    [2.6, 0.66, 1.425],
    [2.4, 0.25, 2.025],
    [2.3, 0.25, 2.1],
    [3.3, 0.25, 2.4],
    [2.7, 0.25, 2.4],
    [2.8, 0.0, 2.475],
    [2.8, -0.25, 2.475],
    [3.525, -0.25, 2.49375],
    [3.525, 0.0, 2.49375],
    [2.9, 0.0, 2.475],
    [2.9, -0.15, 2.475],
    [3.45, -0.15, 2.5125],
    [3.45, 0.0, 2.5125],
    [2.8, 0.0, 2.4],
    [2.8, -0.15, 2.4],
    [3.2, -0.15, 2.4],
    [3.2, 0.0, 2.4],
    [3.525, 0.25, 2.49375],
    [2.8, 0.25, 2.475],
    [3.45, 0.15, 2.5125],
    [2.9, 0.15, 2.475],
    [3.2, 0.15, 2.4],
    [2.8, 0.15, 2.4],
    // 203–268: the lid, from the knob's top down to its edge (204, 205, 215 and 222, near the
    // knob's top, are never used).
    [0.0, 0.0, 3.15],
    [0.0, -0.002, 3.15],
    [0.002, 0.0, 3.15],
    [0.8, 0.0, 3.15],
    [0.8, -0.45, 3.15],
    [0.45, -0.8, 3.15],
    [0.0, -0.8, 3.15],
    [0.0, 0.0, 2.85],
    [0.2, 0.0, 2.7],
    [0.2, -0.112, 2.7],
    [0.112, -0.2, 2.7],
    [0.0, -0.2, 2.7],
    [-0.002, 0.0, 3.15],
    [-0.45, -0.8, 3.15],
    [-0.8, -0.45, 3.15],
    [-0.8, 0.0, 3.15],
    [-0.112, -0.2, 2.7],
    [-0.2, -0.112, 2.7],
    [-0.2, 0.0, 2.7],
    [0.0, 0.002, 3.15],
    [-0.8, 0.45, 3.15],
    [-0.45, 0.8, 3.15],
    [0.0, 0.8, 3.15],
    [-0.2, 0.112, 2.7],
    [-0.112, 0.2, 2.7],
    [0.0, 0.2, 2.7],
    [0.45, 0.8, 3.15],
    [0.8, 0.45, 3.15],
    [0.112, 0.2, 2.7],
    [0.2, 0.112, 2.7],
    [0.4, 0.0, 2.55],
    [0.4, -0.224, 2.55],
    [0.224, -0.4, 2.55],
    [0.0, -0.4, 2.55],
    [1.3, 0.0, 2.55],
    [1.3, -0.728, 2.55],
    [0.728, -1.3, 2.55],
    [0.0, -1.3, 2.55],
    [1.3, 0.0, 2.4],
    [1.3, -0.728, 2.4],
    [0.728, -1.3, 2.4],
    [0.0, -1.3, 2.4],
    [-0.224, -0.4, 2.55],
    [-0.4, -0.224, 2.55],
    [-0.4, 0.0, 2.55],
    [-0.728, -1.3, 2.55],
    [-1.3, -0.728, 2.55],
    [-1.3, 0.0, 2.55],
    [-0.728, -1.3, 2.4],
    [-1.3, -0.728, 2.4],
    [-1.3, 0.0, 2.4],
    [-0.4, 0.224, 2.55],
    [-0.224, 0.4, 2.55],
    [0.0, 0.4, 2.55],
    [-1.3, 0.728, 2.55],
    [-0.728, 1.3, 2.55],
    [0.0, 1.3, 2.55],
    [-1.3, 0.728, 2.4],
    [-0.728, 1.3, 2.4],
    [0.0, 1.3, 2.4],
    [0.224, 0.4, 2.55],
    [0.4, 0.224, 2.55],
    [0.728, 1.3, 2.55],
    [1.3, 0.728, 2.55],
    [0.728, 1.3, 2.4],
    [1.3, 0.728, 2.4],
    // 269–305: the bottom, a later addition to Newell's 28 patches, with copies of its own of the
    // body's lowest points.
    [0.0, 0.0, 0.0],
    [1.5, 0.0, 0.15],
    [1.5, 0.84, 0.15],
    [0.84, 1.5, 0.15],
    [0.0, 1.5, 0.15],
    [1.5, 0.0, 0.075],
    [1.5, 0.84, 0.075],
    [0.84, 1.5, 0.075],
    [0.0, 1.5, 0.075],
    [1.425, 0.0, 0.0],
    [1.425, 0.798, 0.0],
    [0.798, 1.425, 0.0],
    [0.0, 1.425, 0.0],
    [-0.84, 1.5, 0.15],
    [-1.5, 0.84, 0.15],
    [-1.5, 0.0, 0.15],
    [-0.84, 1.5, 0.075],
    [-1.5, 0.84, 0.075],
    [-1.5, 0.0, 0.075],
    [-0.798, 1.425, 0.0],
    [-1.425, 0.798, 0.0],
    [-1.425, 0.0, 0.0],
    [-1.5, -0.84, 0.15],
    [-0.84, -1.5, 0.15],
    [0.0, -1.5, 0.15],
    [-1.5, -0.84, 0.075],
    [-0.84, -1.5, 0.075],
    [0.0, -1.5, 0.075],
    [-1.425, -0.798, 0.0],
    [-0.798, -1.425, 0.0],
    [0.0, -1.425, 0.0],
    [0.84, -1.5, 0.15],
    [1.5, -0.84, 0.15],
    [0.84, -1.5, 0.075],
    [1.5, -0.84, 0.075],
    [0.798, -1.425, 0.0],
    [1.425, -0.798, 0.0],
];

/// Its 32 bicubic patches: 16 indices (0-based) into `POINTS` each, row by row.
// A table, one patch a line (its four rows apart), its numbers in columns.
#[rustfmt::skip]
const PATCHES: [[u16; 16]; 32] = [
    // 0–3: the rim.
    [  0,   1,   2,   3,     4,   5,   6,   7,     8,   9,  10,  11,    12,  13,  14,  15],
    [  3,  16,  17,  18,     7,  19,  20,  21,    11,  22,  23,  24,    15,  25,  26,  27],
    [ 18,  28,  29,  30,    21,  31,  32,  33,    24,  34,  35,  36,    27,  37,  38,  39],
    [ 30,  40,  41,   0,    33,  42,  43,   4,    36,  44,  45,   8,    39,  46,  47,  12],
    // 4–11: the body, in two rings of four.
    [ 12,  13,  14,  15,    48,  49,  50,  51,    52,  53,  54,  55,    56,  57,  58,  59],
    [ 15,  25,  26,  27,    51,  60,  61,  62,    55,  63,  64,  65,    59,  66,  67,  68],
    [ 27,  37,  38,  39,    62,  69,  70,  71,    65,  72,  73,  74,    68,  75,  76,  77],
    [ 39,  46,  47,  12,    71,  78,  79,  48,    74,  80,  81,  52,    77,  82,  83,  56],
    [ 56,  57,  58,  59,    84,  85,  86,  87,    88,  89,  90,  91,    92,  93,  94,  95],
    [ 59,  66,  67,  68,    87,  96,  97,  98,    91,  99, 100, 101,    95, 102, 103, 104],
    [ 68,  75,  76,  77,    98, 105, 106, 107,   101, 108, 109, 110,   104, 111, 112, 113],
    [ 77,  82,  83,  56,   107, 114, 115,  84,   110, 116, 117,  88,   113, 118, 119,  92],
    // 12–15: the handle.
    [120, 121, 122, 123,   124, 125, 126, 127,   128, 129, 130, 131,   132, 133, 134, 135],
    [123, 136, 137, 120,   127, 138, 139, 124,   131, 140, 141, 128,   135, 142, 143, 132],
    [132, 133, 134, 135,   144, 145, 146, 147,   148, 149, 150, 151,    68, 152, 153, 154],
    [135, 142, 143, 132,   147, 155, 156, 144,   151, 157, 158, 148,   154, 159, 160,  68],
    // 16–19: the spout.
    [161, 162, 163, 164,   165, 166, 167, 168,   169, 170, 171, 172,   173, 174, 175, 176],
    [164, 177, 178, 161,   168, 179, 180, 165,   172, 181, 182, 169,   176, 183, 184, 173],
    [173, 174, 175, 176,   185, 186, 187, 188,   189, 190, 191, 192,   193, 194, 195, 196],
    [176, 183, 184, 173,   188, 197, 198, 185,   192, 199, 200, 189,   196, 201, 202, 193],
    // 20–27: the lid, its knob first (its top a pole: the first row one point four times).
    [203, 203, 203, 203,   206, 207, 208, 209,   210, 210, 210, 210,   211, 212, 213, 214],
    [203, 203, 203, 203,   209, 216, 217, 218,   210, 210, 210, 210,   214, 219, 220, 221],
    [203, 203, 203, 203,   218, 223, 224, 225,   210, 210, 210, 210,   221, 226, 227, 228],
    [203, 203, 203, 203,   225, 229, 230, 206,   210, 210, 210, 210,   228, 231, 232, 211],
    [211, 212, 213, 214,   233, 234, 235, 236,   237, 238, 239, 240,   241, 242, 243, 244],
    [214, 219, 220, 221,   236, 245, 246, 247,   240, 248, 249, 250,   244, 251, 252, 253],
    [221, 226, 227, 228,   247, 254, 255, 256,   250, 257, 258, 259,   253, 260, 261, 262],
    [228, 231, 232, 211,   256, 263, 264, 233,   259, 265, 266, 237,   262, 267, 268, 241],
    // 28–31: the bottom (its centre a pole too).
    [269, 269, 269, 269,   278, 279, 280, 281,   274, 275, 276, 277,   270, 271, 272, 273],
    [269, 269, 269, 269,   281, 288, 289, 290,   277, 285, 286, 287,   273, 282, 283, 284],
    [269, 269, 269, 269,   290, 297, 298, 299,   287, 294, 295, 296,   284, 291, 292, 293],
    [269, 269, 269, 269,   299, 304, 305, 278,   296, 302, 303, 274,   293, 300, 301, 270],
];

// Every index of `PATCHES` names one of `POINTS`, checked as the crate compiles: reading the
// control points never leaves a patch out.
const _: () = assert!(indices_in_range(&PATCHES));

/// Whether every index of `patches` is one of `POINTS`'s.
const fn indices_in_range(patches: &[[u16; 16]]) -> bool {
    let mut remaining = patches;
    while let [patch, rest @ ..] = remaining {
        let mut indices: &[u16] = patch;
        while let [index, more @ ..] = indices {
            if *index as usize >= POINTS.len() {
                return false;
            }
            indices = more;
        }
        remaining = rest;
    }
    true
}

/// A point in f64, where the patches are evaluated.
type Point = [f64; 3];

/// A patch's control points, row by row.
type Controls = [[Point; 4]; 4];

/// A place along a cubic: `t` from its first control point and `rest` = 1 − `t`, each the
/// quotient of two whole numbers, so that the same curve walked backwards has them exactly
/// swapped.
#[derive(Clone, Copy, Debug)]
struct Parameter {
    /// How far along, 0 to 1.
    t: f64,
    /// How far from the end, 1 − `t`.
    rest: f64,
}

impl Parameter {
    /// Step `step` of `steps` (at least 1).
    fn at(step: usize, steps: usize) -> Self {
        Self {
            t: step as f64 / steps as f64,
            rest: steps.saturating_sub(step) as f64 / steps as f64,
        }
    }

    /// The derivatives by `t` of [`Self::weights`].
    fn slopes(self) -> [f64; 4] {
        let Self { t, rest } = self;
        [
            -3.0 * rest * rest,
            3.0 * rest * (rest - 2.0 * t),
            3.0 * t * (2.0 * rest - t),
            3.0 * t * t,
        ]
    }

    /// The cubic Bernstein weights of the four control points here. With `t` and `rest`
    /// swapped they come out exactly reversed.
    fn weights(self) -> [f64; 4] {
        let Self { t, rest } = self;
        [
            rest * rest * rest,
            3.0 * (rest * rest) * t,
            3.0 * (t * t) * rest,
            t * t * t,
        ]
    }
}

/// The point of the cubic Bézier curve over `controls` at `at`: the two ends' terms added, the
/// two middle ones added, then the two sums, so that the curve walked backwards (controls and
/// parameter reversed) gives bitwise the same point.
fn cubic(controls: [Point; 4], at: Parameter) -> Point {
    let [first, second, third, last] = controls;
    let [w_first, w_second, w_third, w_last] = at.weights();
    let ends = sum(scaled(first, w_first), scaled(last, w_last));
    let middles = sum(scaled(second, w_second), scaled(third, w_third));
    sum(ends, middles)
}

/// The sum of `controls` weighted by `weights`.
fn weighted(controls: [Point; 4], weights: [f64; 4]) -> Point {
    controls
        .into_iter()
        .zip(weights)
        .fold([0.0; 3], |total, (point, weight)| {
            sum(total, scaled(point, weight))
        })
}

/// The patch's outward normal at step `across`, `down` of `steps`, not normalised: the cross
/// product of its derivatives along its rows and down its columns (zero at a pole, where a
/// row shrinks to a point).
fn patch_normal(controls: &Controls, across: usize, down: usize, steps: usize) -> Point {
    let (u, v) = (Parameter::at(across, steps), Parameter::at(down, steps));
    let rows = |weights: [f64; 4]| controls.map(|row| weighted(row, weights));
    let along_rows = weighted(rows(u.slopes()), v.weights());
    let down_columns = weighted(rows(u.weights()), v.slopes());
    cross(along_rows, down_columns)
}

/// `a`·`b`.
fn dot(a: Point, b: Point) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `a` × `b`.
fn cross([ax, ay, az]: Point, [bx, by, bz]: Point) -> Point {
    [ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx]
}

/// `point` scaled to length 1, or `None` where it is (nearly) zero.
fn unit(point: Point) -> Option<Point> {
    let length = point.iter().map(|c| c * c).sum::<f64>().sqrt();
    (length > 1e-9).then(|| scaled(point, 1.0 / length))
}

/// `point` times `factor`.
fn scaled(point: Point, factor: f64) -> Point {
    point.map(|coordinate| coordinate * factor)
}

/// The sum of `a` and `b`.
fn sum(a: Point, b: Point) -> Point {
    let ([ax, ay, az], [bx, by, bz]) = (a, b);
    [ax + bx, ay + by, az + bz]
}

/// The control points of `patch`, in f64; `None` if it names a point `POINTS` lacks (never:
/// checked as the crate compiles).
fn control_points(patch: &[u16; 16]) -> Option<Controls> {
    let mut controls = [[[0.0; 3]; 4]; 4];
    let slots = controls.iter_mut().flatten();
    for (slot, &index) in slots.zip(patch) {
        *slot = POINTS.get(usize::from(index))?.map(f64::from);
    }
    Some(controls)
}

/// The patch's point at step `across` (along its rows) and `down` (along its columns) of
/// `steps`. On the patch's edge it is the edge curve's, from the edge's four control points
/// only, so that patches sharing an edge give bitwise the same points along it; inside, each
/// row's, then down the column those make.
fn patch_point(controls: &Controls, across: usize, down: usize, steps: usize) -> Point {
    let [first_row, .., last_row] = *controls;
    let along_rows = Parameter::at(across, steps);
    let along_columns = Parameter::at(down, steps);
    match (across, down) {
        (_, 0) => cubic(first_row, along_rows),
        (_, down) if down == steps => cubic(last_row, along_rows),
        (0, _) => cubic(controls.map(|[first, ..]| first), along_columns),
        (across, _) if across == steps => cubic(controls.map(|[.., last]| last), along_columns),
        _ => cubic(controls.map(|row| cubic(row, along_rows)), along_columns),
    }
}

/// Where the surfaces at a vertex turn by more than this cosine's angle (60°), they meet at
/// a crease, and the vertex has a normal for each side.
const CREASE_COS: f64 = 0.5;

/// A mesh as it is built: each distinct vertex once, the triangles over them, and at each
/// triangle's corner the normal of the patch it came from there.
#[derive(Debug, Default)]
struct MeshBuilder {
    /// The vertices, in the order they were first met.
    vertices: Vec<[f32; 3]>,
    /// Each vertex's index, by the bits of its coordinates.
    indices: HashMap<[u32; 3], u32>,
    /// The triangles, anticlockwise seen from outside.
    triangles: Vec<[u32; 3]>,
    /// The patch's unit normal at each triangle's corners (`None` at a pole).
    corners: Vec<[Option<Point>; 3]>,
}

impl MeshBuilder {
    /// The index of the vertex at `point` rounded to f32, added if it is not there yet (a
    /// vertex with bitwise the same coordinates is the same vertex).
    fn vertex(&mut self, point: Point) -> u32 {
        let rounded = point.map(|coordinate| coordinate as f32);
        let next = u32::try_from(self.vertices.len()).unwrap_or(u32::MAX);
        *self
            .indices
            .entry(rounded.map(f32::to_bits))
            .or_insert_with(|| {
                self.vertices.push(rounded);
                next
            })
    }

    /// The unit normals at the triangles' corners, and each corner's among them. The normals
    /// the patches give at a vertex (or the triangle's own, at a pole, where a patch has none,
    /// and where the triangle turns from the patch's by more than 60°) are grouped, each within 60° of its group's first, and a group's mean is its corners'
    /// normal: one normal where the surface is smooth, one per side of a crease (where the
    /// spout's lip folds, where the handle's end touches the body).
    fn corner_normals(&self) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        let position = |index: u32| self.vertices[index as usize].map(f64::from);
        // Each group's first normal and sum; each vertex's groups.
        let mut groups: Vec<(Point, Point)> = Vec::new();
        let mut at_vertex: Vec<Vec<usize>> = vec![Vec::new(); self.vertices.len()];
        let mut corner_groups = Vec::with_capacity(self.triangles.len());
        for (&triangle, corners) in self.triangles.iter().zip(&self.corners) {
            let [a, b, c] = triangle.map(position);
            let face = unit(cross(sum(b, scaled(a, -1.0)), sum(c, scaled(a, -1.0))));
            let mut group_of = |vertex: u32, normal: Option<Point>| {
                // The patch's normal, unless the triangle's chord turns from it by more than
                // a crease's angle (at the spout's tip, where the lip curls within a step).
                let normal = match (normal, face) {
                    (Some(normal), Some(face)) if dot(normal, face) > CREASE_COS => normal,
                    (normal, face) => face.or(normal).unwrap_or([0.0, 0.0, 1.0]),
                };
                let near = at_vertex[vertex as usize]
                    .iter()
                    .copied()
                    .find(|&group| dot(groups[group].0, normal) > CREASE_COS);
                let group = near.unwrap_or_else(|| {
                    groups.push((normal, [0.0; 3]));
                    at_vertex[vertex as usize].push(groups.len() - 1);
                    groups.len() - 1
                });
                groups[group].1 = sum(groups[group].1, normal);
                u32::try_from(group).unwrap_or(u32::MAX)
            };
            let [p, q, r] = triangle;
            let [np, nq, nr] = *corners;
            corner_groups.push([group_of(p, np), group_of(q, nq), group_of(r, nr)]);
        }
        let normals = groups
            .iter()
            .map(|&(first, total)| unit(total).unwrap_or(first).map(|c| c as f32))
            .collect();
        (normals, corner_groups)
    }

    /// The patch tessellated with `steps` × `steps` quads, two triangles each.
    fn add_patch(&mut self, controls: &Controls, steps: usize) {
        let grid: Vec<Vec<(u32, Option<Point>)>> = (0..=steps)
            .map(|down| {
                (0..=steps)
                    .map(|across| {
                        (
                            self.vertex(patch_point(controls, across, down, steps)),
                            unit(patch_normal(controls, across, down, steps)),
                        )
                    })
                    .collect()
            })
            .collect();
        for (row, next_row) in grid.iter().zip(grid.iter().skip(1)) {
            let upper = row.iter().zip(row.iter().skip(1));
            let lower = next_row.iter().zip(next_row.iter().skip(1));
            for ((&first, &second), (&fourth, &third)) in upper.zip(lower) {
                self.add_quad([first, second, third, fourth]);
            }
        }
    }

    /// The quad with these corners and the patch's normals there (in the order of the
    /// patch's rows, then back along the next row: anticlockwise from outside, for every patch
    /// of Newell's) as two triangles, leaving out one that has two corners the same (at a
    /// pole).
    fn add_quad(&mut self, [first, second, third, fourth]: [(u32, Option<Point>); 4]) {
        for corners in [[first, second, third], [first, third, fourth]] {
            let [a, b, c] = corners.map(|(index, _)| index);
            if a != b && b != c && c != a {
                self.triangles.push([a, b, c]);
                self.corners.push(corners.map(|(_, normal)| normal));
            }
        }
    }
}

/// The teapot tessellated with `steps` × `steps` quads per patch, two triangles each: its
/// vertices and its triangles (indices into them, anticlockwise seen from outside).
///
/// Patches that share an edge share its vertices: each point is evaluated in f64 and rounded
/// to f32 once, a point on a patch's edge from that edge's control points alone (so that the
/// two patches give bitwise the same point), and vertices whose coordinates are bitwise the
/// same are one vertex. Of a quad at a pole (the lid knob's top, the bottom's centre), the
/// triangle with two corners the same is left out.
///
/// `steps` is taken as at least 1 and at most 8000 (beyond that the `u32` indices run out).
#[must_use]
pub fn teapot(steps: usize) -> Teapot {
    let steps = steps.clamp(1, MOST_STEPS);
    let mut mesh = MeshBuilder::default();
    for controls in PATCHES.iter().filter_map(control_points) {
        mesh.add_patch(&controls, steps);
    }
    let (normals, corner_normals) = mesh.corner_normals();
    Teapot {
        steps,
        vertices: mesh.vertices,
        triangles: mesh.triangles,
        normals,
        corner_normals,
    }
}

/// The teapot tessellated ([`teapot`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Teapot {
    /// The steps per patch it was tessellated with.
    pub steps: usize,
    /// The vertices.
    pub vertices: Vec<[f32; 3]>,
    /// The triangles, as indices into the vertices, anticlockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// The surface's unit normals at the triangles' corners, for smooth shading.
    pub normals: Vec<[f32; 3]>,
    /// Each triangle's corners' normals, as indices into `normals`.
    pub corner_normals: Vec<[u32; 3]>,
}

impl Teapot {
    /// The teapot as Wavefront OBJ text ([`obscura_scene::obj_text`]) after a comment line
    /// saying what made it: with [`SHIPPED_STEPS`], `host/scenes/teapot.obj`.
    #[must_use]
    pub fn obj_text(&self) -> String {
        let steps = self.steps;
        format!(
            "# The Utah teapot: Newell's 32 Bézier patches, each tessellated into {steps} × \
             {steps} quads by obscura_host::teapot, with the surface's normal at each vertex\n{}",
            obscura_scene::obj_text(
                &self.vertices,
                &self.triangles,
                Some(CornerNormals {
                    normals: &self.normals,
                    corners: &self.corner_normals,
                })
            )
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    /// The edges of `triangles`, each as its two corners in ascending order, with how many
    /// triangles have it.
    fn edge_uses(triangles: &[[u32; 3]]) -> HashMap<[u32; 2], usize> {
        let mut uses = HashMap::new();
        for &[a, b, c] in triangles {
            for (from, to) in [(a, b), (b, c), (c, a)] {
                *uses.entry([from.min(to), from.max(to)]).or_insert(0) += 1;
            }
        }
        uses
    }

    /// The volume the triangles enclose, signed: positive when they face outwards.
    fn signed_volume(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> f64 {
        let corner = |index: u32| vertices[index as usize].map(f64::from);
        triangles
            .iter()
            .map(|&[a, b, c]| {
                let ([ax, ay, az], [bx, by, bz], [cx, cy, cz]) = (corner(a), corner(b), corner(c));
                let cross = [by * cz - bz * cy, bz * cx - bx * cz, bx * cy - by * cx];
                (ax * cross[0] + ay * cross[1] + az * cross[2]) / 6.0
            })
            .sum()
    }

    #[test]
    fn the_shipped_teapot_is_the_generated_one() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/teapot.obj");
        let generated = teapot(usize::from(SHIPPED_STEPS)).obj_text();
        if std::env::var_os("OBSCURA_WRITE_TEAPOT").is_some() {
            std::fs::write(path, &generated).unwrap();
        }
        let shipped = std::fs::read_to_string(path).unwrap_or_default();
        assert!(
            shipped == generated,
            "{path} is not the teapot obscura_host::teapot makes: regenerate with \
             OBSCURA_WRITE_TEAPOT=1 cargo test -p obscura-host teapot"
        );
    }

    #[test]
    fn the_shipped_teapot_has_552_triangles_on_301_vertices() {
        let Teapot {
            vertices,
            triangles,
            ..
        } = teapot(usize::from(SHIPPED_STEPS));
        // 32 patches of 3 × 3 quads, two triangles each, but the 4 patches of the lid's knob
        // and the 4 of the bottom each have 3 quads at their pole, with one triangle each
        // left out.
        assert_eq!(triangles.len(), 32 * 9 * 2 - 8 * 3);
        assert_eq!(vertices.len(), 301);
        let corners: HashSet<u32> = triangles.iter().flatten().copied().collect();
        assert_eq!(
            corners.len(),
            vertices.len(),
            "every vertex is a triangle's corner"
        );
    }

    #[test]
    fn the_teapot_is_watertight_where_patches_meet() {
        for steps in [2, usize::from(SHIPPED_STEPS), 5] {
            let Teapot { triangles, .. } = teapot(steps);
            let uses = edge_uses(&triangles);
            assert!(
                uses.values().all(|&n| n == 1 || n == 2),
                "{steps} steps: {uses:?}"
            );
            let open = uses.values().filter(|&&n| n == 1).count();
            // Newell's teapot is open where its parts meet without sharing control points,
            // 16 patch edges of `steps` mesh edges each: the rim's inner edge and the lid's
            // outer one (4 patches each: the lid sits in the opening without touching the
            // rim), both ends of the handle and both of the spout (2 patches each: where they
            // meet the body, which they pierce rather than join, and the spout's tip).
            // Everything else, the bottom's seam with the body included (the same points
            // under other indices), is closed.
            assert_eq!(open, 16 * steps, "{steps} steps");
        }
    }

    #[test]
    fn the_teapots_normals_are_unit_and_turn_with_its_faces() {
        let mesh = teapot(usize::from(SHIPPED_STEPS));
        let corner = |index: u32| mesh.vertices[index as usize].map(f64::from);
        let mut least = f64::INFINITY;
        for (&[a, b, c], normals) in mesh.triangles.iter().zip(&mesh.corner_normals) {
            let face = cross(
                sum(corner(b), scaled(corner(a), -1.0)),
                sum(corner(c), scaled(corner(a), -1.0)),
            );
            let face = unit(face).expect("every triangle has area");
            for &normal in normals {
                let normal = mesh.normals[normal as usize].map(f64::from);
                let length = dot(normal, normal).sqrt();
                assert!((length - 1.0).abs() < 1e-6, "{length}");
                least = least.min(dot(normal, face));
            }
        }
        // The normal at a corner is within 70° of the triangle's own (60° from the patch's
        // or the triangle's own normal, and the mean of a group within 60° of its first); it
        // is the same at a vertex on both sides of an edge except where the surface folds.
        assert!(least > 0.34, "{least}");
        // A vertex's several normals are those of a fold, more than 60° apart; at 3 steps a
        // patch the rim's lip, the lid's knob, the spout's tip and the handle's lower end
        // fold (43 vertices); the rest of the surface (the body, the lid, the bottom) is
        // smooth.
        let mut at_vertex: HashMap<u32, HashSet<u32>> = HashMap::new();
        for (triangle, normals) in mesh.triangles.iter().zip(&mesh.corner_normals) {
            for (&vertex, &normal) in triangle.iter().zip(normals) {
                at_vertex.entry(vertex).or_default().insert(normal);
            }
        }
        let normal = |i: u32| mesh.normals[i as usize].map(f64::from);
        for normals in at_vertex.values() {
            for (&i, &j) in normals
                .iter()
                .flat_map(|i| normals.iter().map(move |j| (i, j)))
            {
                assert!(i == j || dot(normal(i), normal(j)) < CREASE_COS);
            }
        }
        let folded = at_vertex
            .values()
            .filter(|normals| normals.len() > 1)
            .count();
        assert!(folded < mesh.vertices.len() / 5, "{folded} vertices folded");
    }

    #[test]
    fn the_teapot_faces_outwards() {
        let Teapot {
            vertices,
            triangles,
            ..
        } = teapot(usize::from(SHIPPED_STEPS));
        // Neighbouring triangles walk their shared edge in opposite directions: one winding
        // all over.
        let mut directed = HashSet::new();
        for &[a, b, c] in &triangles {
            for edge in [(a, b), (b, c), (c, a)] {
                assert!(
                    directed.insert(edge),
                    "edge {edge:?} walked twice the same way"
                );
            }
        }
        // Anticlockwise from outside encloses a positive volume: about 25.9 for the surface
        // itself (as 32 steps measure it), less for 3 steps' chords, which cut inside it.
        let volume = signed_volume(&vertices, &triangles);
        assert!((24.0..24.5).contains(&volume), "{volume}");
        // And it is Newell's teapot, at Newell's size.
        let extent = |axis: usize| {
            let values = vertices.iter().map(|vertex| vertex[axis]);
            let low = values.clone().fold(f32::INFINITY, f32::min);
            (low, values.fold(f32::NEG_INFINITY, f32::max))
        };
        let expected = [(-3.0, 3.43), (-2.0, 2.0), (0.0, 3.15)];
        for (axis, (low, high)) in expected.into_iter().enumerate() {
            let (found_low, found_high) = extent(axis);
            assert!(
                (found_low - low).abs() < 0.01 && (found_high - high).abs() < 0.01,
                "axis {axis}: {found_low} to {found_high}"
            );
        }
    }
}
