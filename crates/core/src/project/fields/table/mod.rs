//! The table itself: every field of the project file ([`FIELDS`]) and the sections they
//! are grouped in ([`SECTIONS`]), in document order.

use super::{Field, Id, Kind};
use crate::project::fields::id;

fn u(id: Id, unit: &'static str, kind: Kind, doc: &'static str) -> Field {
    Field {
        path: id.path,
        unit,
        kind,
        doc,
        get: id.get,
        set: id.set,
    }
}

fn f(id: Id, unit: &'static str, min: f32, max: f32, doc: &'static str) -> Field {
    u(id, unit, Kind::Float { min, max }, doc)
}

fn i(id: Id, unit: &'static str, min: u64, max: u64, doc: &'static str) -> Field {
    u(id, unit, Kind::Int { min, max }, doc)
}

fn k(id: Id, kind: Kind, doc: &'static str) -> Field {
    u(id, "", kind, doc)
}

const HU: &str = "height units";
const YEARS: &str = "years";
const MAX_SEED: u64 = u64::MAX;
const CURVE_SHAPES: &[&str] = &["smoothstep", "linear"];
const AXES: &[&str] = &["auto", "+x", "-x", "+y", "-y", "+z", "-z"];

macro_rules! curve {
    ($name:ident, $what:literal) => {
        [
            f(
                id!(age.$name.onset_years),
                YEARS,
                0.0,
                150.0,
                concat!($what, ": age at which it starts"),
            ),
            f(
                id!(age.$name.full_years),
                YEARS,
                0.0,
                150.0,
                concat!($what, ": age at which it is complete (≥ onset)"),
            ),
            k(
                id!(age.$name.shape),
                Kind::Choice(CURVE_SHAPES),
                concat!($what, ": ramp between onset and full age"),
            ),
        ]
    };
}

macro_rules! mean_spread {
    ($($m:ident).+, $unit:expr, $lo:expr, $hi:expr, $spread:expr, $what:literal) => {
        [
            f(
                id!($($m).+.mean),
                $unit,
                $lo,
                $hi,
                concat!($what, ", mean"),
            ),
            f(
                id!($($m).+.spread),
                $unit,
                0.0,
                $spread,
                concat!($what, ", ± spread (uniform per feature)"),
            ),
        ]
    };
}

mod aging;

/// Sections in document order, with one line each for the docs page.
pub const SECTIONS: &[(&str, &str)] = &[
    (
        "",
        "Top level: the format version, the skin patch of the micro-relief, the seed.",
    ),
    ("mesh", "The head the maps are made for."),
    (
        "large",
        "Large wrinkles: muscle fibres from wrinkle description files (docs/models.md \"Large wrinkles\").",
    ),
    ("pores", "Pores of the micro-relief ([P] eq. 15, 3, 11)."),
    ("furrows", "Furrows between pores ([P] eq. 16)."),
    ("noise", "Fractal noise added to the heights ([P] eq. 17)."),
    (
        "warp",
        "Domain warp of pores and furrows: the same fBm, its own settings.",
    ),
    ("overlap", "Log-smoothed overlaps of features ([P] eq. 18)."),
    ("normal", "Height map to normal map."),
    (
        "fine",
        "The tileable fine-wrinkle map, blended in with age ([T] §5.2).",
    ),
    (
        "hair",
        "Hair recession (transition texture), instances, graying and Kajiya–Kay shading ([T] §6).",
    ),
    (
        "skin",
        "Skin shading, and its colour with age: spots, uneven tone, paling, lips and brows fading (docs/models.md §12).",
    ),
    (
        "shape",
        "Age changes the shape: regions of the face descending, hollowing and bulging, each with its strength (docs/models.md §13).",
    ),
    (
        "age",
        "The age: the current t, the years it stands for, and each layer's age curve (docs/models.md \"Age\").",
    ),
    (
        "view",
        "How the head is shown: POM, light, camera (saved with the project).",
    ),
];

/// Every field of the project, in document order.
pub static FIELDS: std::sync::LazyLock<Vec<Field>> = std::sync::LazyLock::new(|| {
    let mut v = vec![
        i(
            id!(version),
            "",
            1,
            2,
            "format version (1 is read and migrated)",
        ),
        f(
            id!(map_size_mm),
            "mm",
            1.0,
            1000.0,
            "side of the square skin patch the micro-relief map covers",
        ),
        i(
            id!(seed),
            "",
            0,
            MAX_SEED,
            "seed of every random choice of the micro-relief",
        ),
        k(
            id!(tile),
            Kind::Bool,
            "micro-relief tiles: periodic noise, features wrap around the edges",
        ),
        k(
            id!(mesh.path),
            Kind::Path,
            "head mesh file (OBJ, glTF, GLB); null = the built-in mesh",
        ),
        k(
            id!(mesh.builtin),
            Kind::Choice(&["head", "skin-patch"]),
            "built-in mesh used when mesh.path is null",
        ),
        u(
            id!(mesh.metres_per_unit),
            "m",
            Kind::OptFloat {
                min: 1e-5,
                max: 1000.0,
            },
            "metres per mesh unit; null = measured: 1 for the built-in meshes, a mesh file's from its landmarks (outer eye corners ≈ 95 mm apart) or its size (m, dm, cm, mm or inch when close; `agesim mesh-info` says how)",
        ),
        k(
            id!(mesh.landmarks),
            Kind::Landmarks,
            "the head's landmarks, in the mesh file's units: a landmark file ({\"landmarks\": {name: [x, y, z]}}) or the points themselves ({name: [x, y, z]}); null = none",
        ),
        k(
            id!(mesh.up),
            Kind::Choice(AXES),
            "the mesh file's up axis; auto = from the landmarks (chin to brow), else +y",
        ),
        k(
            id!(mesh.forward),
            Kind::Choice(AXES),
            "the mesh file's forward axis, where the face looks; auto = from the landmarks (eyes to nose tip), else +z",
        ),
        k(
            id!(mesh.layout),
            Kind::Choice(&["template", "own-uvs"]),
            "where a mesh file's layers are read: template = the default head fitted to it by its landmarks (mesh.landmarks, else found automatically), own-uvs = at its own UVs as if they were the default head's",
        ),
        k(
            id!(mesh.colour_map),
            Kind::Path,
            "the head's base colour map (PNG, JPEG…, sRGB) over its own UVs: shown, paled with age and exported in the GLB; null = the skin colour (skin.albedo)",
        ),
        k(
            id!(mesh.normal_map),
            Kind::Path,
            "the head's tangent-space normal map over its own UVs: the wrinkles and skin relief are combined onto it (reoriented normal mapping) in the view and the exports; null = none",
        ),
        k(
            id!(mesh.normal_map_convention),
            Kind::Choice(&["opengl", "directx"]),
            "the head's normal map's green channel: up (OpenGL, glTF's) or down (DirectX)",
        ),
        k(
            id!(mesh.skin_parts),
            Kind::OptNames,
            "the parts (objects, materials) that are skin, by name: a part is skin when its name contains one of these; null = by their names (all but eyes, teeth, tongue, lashes, brows). Only skin gets wrinkles and hair",
        ),
        k(
            id!(mesh.maps_flip_v),
            Kind::Bool,
            "turn the colour and normal maps upside down (for a head whose UVs use the other v convention than its pictures)",
        ),
        k(
            id!(large.enabled),
            Kind::Bool,
            "bake the large-wrinkle layer (--layers overrides)",
        ),
        k(
            id!(large.wrinkles),
            Kind::Paths,
            "wrinkle description files; empty = the default head's files",
        ),
        k(
            id!(large.mask),
            Kind::Path,
            "grey mask multiplying the layer; null = the default head's mask with the default files",
        ),
        f(
            id!(large.gamma),
            "",
            0.01,
            10.0,
            "shaping γ of the normalised depth (1: the profiles as they are; [T]: 0.4)",
        ),
        f(
            id!(large.depth),
            HU,
            0.0,
            10.0,
            "height of a normalised large wrinkle of 1 (past 80 years, times the old-age depth gain: 1.7 at 85, 2.4 from 90)",
        ),
        k(id!(pores.enabled), Kind::Bool, "bake pores"),
        i(
            id!(pores.count),
            "",
            0,
            200_000,
            "exact number of pores (unless density_per_cm2 is set)",
        ),
        k(
            id!(pores.density_per_cm2),
            Kind::OptFloat {
                min: 0.0,
                max: 10_000.0,
            },
            "pores per cm²; when set, count = round(density × area)",
        ),
        k(
            id!(pores.placement),
            Kind::Choice(&["blue-noise", "uniform"]),
            "Poisson disc (minimum spacing) or independent uniform",
        ),
    ];
    v.extend(mean_spread!(
        pores.radius_mm,
        "mm",
        0.0,
        1.0,
        1.0,
        "pore radius R"
    ));
    v.extend(mean_spread!(
        pores.depth,
        HU,
        0.0,
        4.0,
        4.0,
        "pore depth dmax"
    ));
    v.extend(mean_spread!(
        pores.falloff,
        "",
        -1.5,
        1.5,
        1.5,
        "pore falloff α (negative = goose skin)"
    ));
    v.extend([
        k(
            id!(pores.profile),
            Kind::Choice(&["gaussian", "quadratic", "quartic"]),
            "radial profile: eq. 15, eq. 3 or eq. 11",
        ),
        k(
            id!(pores.rim),
            Kind::Choice(&["smooth", "exact"]),
            "eq. 15's rim: windowed to 0, or the exact step",
        ),
        f(
            id!(pores.elongation),
            "",
            1.0,
            4.0,
            "pore aspect ratio at full age (age.furrows curve), along the tension lines θ; 1 = round",
        ),
        k(id!(furrows.enabled), Kind::Bool, "bake furrows"),
        i(
            id!(furrows.links_per_pore),
            "",
            1,
            8,
            "each pore links to its k nearest neighbours",
        ),
        k(
            id!(furrows.max_count),
            Kind::OptInt {
                min: 0,
                max: u32::MAX as u64,
            },
            "keep at most this many links (seeded subset); null = all",
        ),
    ]);
    v.extend(mean_spread!(
        furrows.depth,
        HU,
        0.0,
        2.5,
        2.5,
        "furrow depth A"
    ));
    v.extend(mean_spread!(
        furrows.width_mm,
        "mm",
        0.0,
        1.5,
        1.5,
        "furrow half-width ω"
    ));
    v.extend([
        f(
            id!(furrows.direction_deg),
            "degrees",
            -360.0,
            360.0,
            "preferred direction θ, counter-clockwise from +u",
        ),
        f(
            id!(furrows.direction_strength),
            "",
            0.0,
            1.0,
            "how much shallower links across θ are",
        ),
        f(
            id!(furrows.anisotropy),
            "",
            0.0,
            1.0,
            "how much more the furrows follow θ at full age (age.furrows curve)",
        ),
        f(
            id!(furrows.taper),
            "",
            0.01,
            0.5,
            "fraction of the length over which each end narrows",
        ),
        f(
            id!(noise.details),
            "octaves",
            0.0,
            12.0,
            "octaves, fractional allowed; 0 = no noise",
        ),
        f(
            id!(noise.roughness),
            "",
            0.0,
            1.0,
            "amplitude gain per octave",
        ),
        f(
            id!(noise.lacunarity),
            "",
            0.1,
            4.0,
            "frequency factor per octave",
        ),
        f(
            id!(noise.scale_mm),
            "mm",
            0.01,
            1000.0,
            "first-octave lattice cell",
        ),
        f(
            id!(noise.strength),
            HU,
            0.0,
            10.0,
            "λ: amplitude of the normalised fBm",
        ),
        f(
            id!(warp.strength_mm),
            "mm",
            0.0,
            10.0,
            "largest displacement per axis; 0 = no warp",
        ),
        f(
            id!(warp.details),
            "octaves",
            0.0,
            6.0,
            "octaves of the warp",
        ),
        f(
            id!(warp.roughness),
            "",
            0.0,
            1.0,
            "amplitude gain per octave",
        ),
        f(
            id!(warp.lacunarity),
            "",
            0.1,
            4.0,
            "frequency factor per octave",
        ),
        f(
            id!(warp.scale_mm),
            "mm",
            0.01,
            1000.0,
            "first-octave lattice cell",
        ),
        f(
            id!(overlap.beta),
            "1/height unit",
            0.01,
            40.0,
            "sharpness β; β × the deepest feature ≤ 80",
        ),
        f(id!(overlap.n), "", 1.0, 100.0, "smoothing N"),
        f(
            id!(normal.strength),
            "UV per height unit",
            0.0,
            1000.0,
            "slope per height step of the exported normal map",
        ),
        k(
            id!(normal.convention),
            Kind::Choice(&["opengl", "directx"]),
            "green up (OpenGL) or down (DirectX)",
        ),
    ]);
    v.extend(aging::rows());
    v
});
