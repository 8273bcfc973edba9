//! The OpenGL enum values the importer reads (from the OpenGL 1.x
//! specification and its ARB/EXT extensions; captures record enums by
//! value), and their names for messages and the summary.

pub const POINTS: i64 = 0x0000;
pub const LINES: i64 = 0x0001;
pub const LINE_LOOP: i64 = 0x0002;
pub const LINE_STRIP: i64 = 0x0003;
pub const TRIANGLES: i64 = 0x0004;
pub const TRIANGLE_STRIP: i64 = 0x0005;
pub const TRIANGLE_FAN: i64 = 0x0006;
pub const QUADS: i64 = 0x0007;
pub const QUAD_STRIP: i64 = 0x0008;
pub const POLYGON: i64 = 0x0009;

pub const NEVER: i64 = 0x0200;
pub const ALWAYS: i64 = 0x0207;

pub const ZERO: i64 = 0;
pub const ONE: i64 = 1;
pub const SRC_COLOR: i64 = 0x0300;
pub const ONE_MINUS_SRC_COLOR: i64 = 0x0301;
pub const SRC_ALPHA: i64 = 0x0302;
pub const ONE_MINUS_SRC_ALPHA: i64 = 0x0303;
pub const DST_ALPHA: i64 = 0x0304;
pub const ONE_MINUS_DST_ALPHA: i64 = 0x0305;
pub const DST_COLOR: i64 = 0x0306;
pub const ONE_MINUS_DST_COLOR: i64 = 0x0307;

pub const FRONT: i64 = 0x0404;
pub const BACK: i64 = 0x0405;
pub const FRONT_AND_BACK: i64 = 0x0408;
pub const CW: i64 = 0x0900;
pub const CCW: i64 = 0x0901;

pub const CULL_FACE: i64 = 0x0B44;
pub const DEPTH_TEST: i64 = 0x0B71;
pub const ALPHA_TEST: i64 = 0x0BC0;
pub const BLEND: i64 = 0x0BE2;
pub const SCISSOR_TEST: i64 = 0x0C11;
pub const TEXTURE_2D: i64 = 0x0DE1;
pub const POLYGON_OFFSET_FILL: i64 = 0x8037;
pub const TEXTURE_GEN_S: i64 = 0x0C60;
pub const TEXTURE_GEN_Q: i64 = 0x0C63;
pub const TEXTURE_1D: i64 = 0x0DE0;
pub const TEXTURE_3D: i64 = 0x806F;
pub const TEXTURE_CUBE_MAP: i64 = 0x8513;

pub const UNPACK_ROW_LENGTH: i64 = 0x0CF2;
pub const UNPACK_SKIP_ROWS: i64 = 0x0CF3;
pub const UNPACK_SKIP_PIXELS: i64 = 0x0CF4;
pub const UNPACK_ALIGNMENT: i64 = 0x0CF5;

pub const BYTE: i64 = 0x1400;
pub const UNSIGNED_BYTE: i64 = 0x1401;
pub const SHORT: i64 = 0x1402;
pub const UNSIGNED_SHORT: i64 = 0x1403;
pub const INT: i64 = 0x1404;
pub const UNSIGNED_INT: i64 = 0x1405;
pub const FLOAT: i64 = 0x1406;
pub const DOUBLE: i64 = 0x140A;

pub const MODELVIEW: i64 = 0x1700;
pub const PROJECTION: i64 = 0x1701;
pub const TEXTURE: i64 = 0x1702;

pub const ALPHA: i64 = 0x1906;
pub const RGB: i64 = 0x1907;
pub const RGBA: i64 = 0x1908;
pub const LUMINANCE: i64 = 0x1909;
pub const LUMINANCE_ALPHA: i64 = 0x190A;
pub const BGR: i64 = 0x80E0;
pub const BGRA: i64 = 0x80E1;

pub const NEAREST: i64 = 0x2600;
pub const LINEAR: i64 = 0x2601;
pub const NEAREST_MIPMAP_NEAREST: i64 = 0x2700;
pub const LINEAR_MIPMAP_NEAREST: i64 = 0x2701;
pub const NEAREST_MIPMAP_LINEAR: i64 = 0x2702;
pub const LINEAR_MIPMAP_LINEAR: i64 = 0x2703;
pub const TEXTURE_MAG_FILTER: i64 = 0x2800;
pub const TEXTURE_MIN_FILTER: i64 = 0x2801;
pub const TEXTURE_WRAP_S: i64 = 0x2802;
pub const TEXTURE_WRAP_T: i64 = 0x2803;
pub const TEXTURE_WRAP_R: i64 = 0x8072;
pub const MIRRORED_REPEAT: i64 = 0x8370;
pub const REPEAT: i64 = 0x2901;

pub const TEXTURE_ENV: i64 = 0x2300;
pub const TEXTURE_ENV_MODE: i64 = 0x2200;
pub const MODULATE: i64 = 0x2100;
pub const DECAL: i64 = 0x2101;
pub const ADD: i64 = 0x0104;
pub const REPLACE: i64 = 0x1E01;
pub const BLEND_ENV: i64 = 0x0BE2;
pub const COMBINE: i64 = 0x8570;

pub const VERTEX_ARRAY: i64 = 0x8074;
pub const NORMAL_ARRAY: i64 = 0x8075;
pub const COLOR_ARRAY: i64 = 0x8076;
pub const TEXTURE_COORD_ARRAY: i64 = 0x8078;

pub const TEXTURE0: i64 = 0x84C0;
pub const ARRAY_BUFFER: i64 = 0x8892;
pub const ELEMENT_ARRAY_BUFFER: i64 = 0x8893;

pub const DEPTH_BUFFER_BIT: i64 = 0x0100;
pub const COLOR_BUFFER_BIT: i64 = 0x4000;

/// The name of an enum the importer knows of (for messages and the
/// summary), else its value in hexadecimal.
pub fn name(v: i64) -> String {
    let known: &[(i64, &str)] = &[
        (TRIANGLES, "GL_TRIANGLES"),
        (TRIANGLE_STRIP, "GL_TRIANGLE_STRIP"),
        (TRIANGLE_FAN, "GL_TRIANGLE_FAN"),
        (QUADS, "GL_QUADS"),
        (QUAD_STRIP, "GL_QUAD_STRIP"),
        (POLYGON, "GL_POLYGON"),
        (ALPHA, "GL_ALPHA"),
        (RGB, "GL_RGB"),
        (RGBA, "GL_RGBA"),
        (LUMINANCE, "GL_LUMINANCE"),
        (LUMINANCE_ALPHA, "GL_LUMINANCE_ALPHA"),
        (BGR, "GL_BGR"),
        (BGRA, "GL_BGRA"),
        (UNSIGNED_BYTE, "GL_UNSIGNED_BYTE"),
        (FLOAT, "GL_FLOAT"),
        (CULL_FACE, "GL_CULL_FACE"),
        (DEPTH_TEST, "GL_DEPTH_TEST"),
        (ALPHA_TEST, "GL_ALPHA_TEST"),
        (BLEND, "GL_BLEND"),
        (SCISSOR_TEST, "GL_SCISSOR_TEST"),
        (TEXTURE_2D, "GL_TEXTURE_2D"),
        (POLYGON_OFFSET_FILL, "GL_POLYGON_OFFSET_FILL"),
        (0x0B50, "GL_LIGHTING"),
        (0x0B60, "GL_FOG"),
        (0x0BD0, "GL_DITHER"),
        (0x0BA1, "GL_NORMALIZE"),
        (0x0B57, "GL_COLOR_MATERIAL"),
        (0x0B20, "GL_LINE_SMOOTH"),
        (0x0C60, "GL_TEXTURE_GEN_S"),
        (0x0C61, "GL_TEXTURE_GEN_T"),
        (0x0C62, "GL_TEXTURE_GEN_R"),
        (0x0C63, "GL_TEXTURE_GEN_Q"),
        (0x0B90, "GL_STENCIL_TEST"),
        (0x809D, "GL_MULTISAMPLE"),
        (0x0B10, "GL_POINT_SMOOTH"),
        (0x0B41, "GL_POLYGON_SMOOTH"),
        (0x2A02, "GL_POLYGON_OFFSET_LINE"),
        (0x3000, "GL_CLIP_PLANE0"),
        (0x4000, "GL_LIGHT0"),
        (TEXTURE_1D, "GL_TEXTURE_1D"),
        (TEXTURE_3D, "GL_TEXTURE_3D"),
        (TEXTURE_CUBE_MAP, "GL_TEXTURE_CUBE_MAP"),
        (0x8191, "GL_GENERATE_MIPMAP"),
        (0x813C, "GL_TEXTURE_BASE_LEVEL"),
        (0x813D, "GL_TEXTURE_MAX_LEVEL"),
        (0x84FE, "GL_TEXTURE_MAX_ANISOTROPY_EXT"),
        (0x8501, "GL_TEXTURE_LOD_BIAS"),
        (0x8571, "GL_COMBINE_RGB"),
        (0x8572, "GL_COMBINE_ALPHA"),
    ];
    known
        .iter()
        .find(|(k, _)| *k == v)
        .map_or_else(|| format!("{v:#06x}"), |(_, n)| (*n).to_string())
}
