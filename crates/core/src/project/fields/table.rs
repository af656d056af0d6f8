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
            "height of a normalised large wrinkle of 1",
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
        f(id!(noise.roughness), "", 0.0, 1.0, "amplitude gain per octave"),
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
        f(id!(warp.details), "octaves", 0.0, 6.0, "octaves of the warp"),
        f(id!(warp.roughness), "", 0.0, 1.0, "amplitude gain per octave"),
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
        k(id!(fine.enabled), Kind::Bool, "show the fine wrinkles"),
        k(
            id!(fine.tile),
            Kind::Path,
            "tileable grey height image; null = generated from the fields below",
        ),
        f(
            id!(fine.size_mm),
            "mm",
            1.0,
            500.0,
            "side of one tile on the skin",
        ),
        f(
            id!(fine.strength),
            "tile UV per height unit",
            0.0,
            1.0,
            "normal strength of the tile",
        ),
        i(
            id!(fine.size_px),
            "px",
            16,
            8192,
            "resolution of the generated tile",
        ),
        i(
            id!(fine.creases),
            "",
            1,
            100_000,
            "number of creases in the generated tile",
        ),
        f(
            id!(fine.length),
            "tile sides",
            0.001,
            0.5,
            "mean crease length",
        ),
        f(
            id!(fine.width),
            "tile sides",
            0.0001,
            0.05,
            "crease valley half-width σ",
        ),
        f(
            id!(fine.crossing_deg),
            "degrees",
            0.0,
            180.0,
            "angle between the two crease families",
        ),
        f(
            id!(fine.spread_deg),
            "degrees",
            0.0,
            90.0,
            "random spread of each crease's direction",
        ),
        i(id!(fine.seed), "", 0, MAX_SEED, "seed of the generated tile"),
        k(id!(hair.enabled), Kind::Bool, "generate and show hair"),
        k(
            id!(hair.outer_mask),
            Kind::Path,
            "grey mask of the hair at t = 0; null = the default head's",
        ),
        k(
            id!(hair.inner_mask),
            Kind::Path,
            "grey mask of the hair left at t = 1; null = the default head's",
        ),
        f(
            id!(hair.density_per_cm2),
            "1/cm²",
            0.0,
            2000.0,
            "hairs per cm² of scalp",
        ),
        k(
            id!(hair.metric),
            Kind::Choice(&["chebyshev", "euclidean"]),
            "distance of the recession fronts: square or round",
        ),
        k(
            id!(hair.transition_size_px),
            Kind::OptInt {
                min: 1,
                max: 16_384,
            },
            "transition texture side; null = the masks' size",
        ),
        i(id!(hair.seed), "", 0, MAX_SEED, "seed of the hair placement"),
        f(
            id!(hair.max_deviation_deg),
            "degrees",
            0.0,
            90.0,
            "random deviation of a hair from the surface normal",
        ),
        f(id!(hair.length_mm), "mm", 0.0, 500.0, "hair length"),
        k(id!(hair.base_colour), Kind::Colour, "colour before graying"),
        k(id!(hair.gray_colour), Kind::Colour, "colour when fully gray"),
        f(
            id!(hair.graying_onset_min_years),
            YEARS,
            0.0,
            150.0,
            "earliest age at which a hair starts to gray",
        ),
        f(
            id!(hair.graying_onset_max_years),
            YEARS,
            0.0,
            150.0,
            "latest age at which a hair starts to gray",
        ),
        k(
            id!(hair.graying_ramp),
            Kind::Choice(&["linear", "smoothstep"]),
            "how a hair grays after its onset",
        ),
        f(
            id!(hair.thinning),
            "",
            0.0,
            1.0,
            "fraction of the hair (the fringe that stays too) lost by the old end, hair by hair",
        ),
        f(
            id!(hair.taper_mm),
            "mm",
            0.0,
            100.0,
            "hair shortens over this distance toward the edge of its region (the nape, round the ears)",
        ),
        f(
            id!(hair.scalp_tint),
            "",
            0.0,
            1.0,
            "how far the scalp under the hair takes the hair's colour in the 3D view (the roots of short hair; not exported)",
        ),
        k(
            id!(hair.brows),
            Kind::Bool,
            "draw eyebrow hairs over the brows and lashes on the upper lids in the 3D view, the brows graying and growing bushier with age, the lashes thinning (a fitted head; not exported)",
        ),
        f(id!(hair.k_diff), "", 0.0, 4.0, "Kajiya–Kay diffuse weight"),
        f(id!(hair.k_spec), "", 0.0, 4.0, "Kajiya–Kay specular weight"),
        f(
            id!(hair.shininess),
            "",
            1.0,
            1000.0,
            "Kajiya–Kay specular exponent",
        ),
        f(id!(hair.k_amb), "", 0.0, 1.0, "ambient term"),
        k(id!(skin.albedo), Kind::Colour, "skin colour at the young end"),
        k(
            id!(skin.pale_albedo),
            Kind::Colour,
            "the tone skin pales toward",
        ),
        f(
            id!(skin.pale_amount),
            "",
            0.0,
            1.0,
            "how far toward pale_albedo at full paling",
        ),
        f(
            id!(skin.spots_per_cm2),
            "/cm²",
            0.0,
            2.0,
            "age spots (solar lentigines, 2–10 mm) per cm² of sun-exposed skin at full age",
        ),
        f(
            id!(skin.spot_strength),
            "",
            0.0,
            1.0,
            "how dark an age spot is",
        ),
        f(
            id!(skin.mottle),
            "",
            0.0,
            1.0,
            "mottled melanin (uneven tone) on sun-exposed skin at full age",
        ),
        f(
            id!(skin.redness),
            "",
            0.0,
            1.0,
            "redness and thread veins on the cheeks and nose at full age",
        ),
        f(
            id!(skin.under_eye),
            "",
            0.0,
            1.0,
            "shadow under the eyes (lower lid, tear trough) at full age, on the contrast curve",
        ),
        f(id!(skin.yellowing), "", 0.0, 1.0, "yellowing at full paling"),
        f(
            id!(skin.contrast_loss),
            "",
            0.0,
            1.0,
            "how far lips and brows fade toward the skin at full age",
        ),
        i(
            id!(skin.colour_seed),
            "",
            0,
            MAX_SEED,
            "seed of the age spots and the uneven tone",
        ),
        k(
            id!(skin.subsurface_colour),
            Kind::Colour,
            "colour of light scattered under the skin",
        ),
        f(
            id!(skin.wrap),
            "",
            0.0,
            1.0,
            "wrap lighting (cheap subsurface scattering)",
        ),
        f(id!(skin.roughness), "", 0.05, 1.0, "specular roughness"),
        f(id!(skin.specular), "", 0.0, 1.0, "specular strength"),
        f(
            id!(age.t),
            "",
            0.0,
            1.0,
            "current age: 0 = young_years, 1 = old_years",
        ),
        f(
            id!(age.young_years),
            YEARS,
            0.0,
            150.0,
            "the age t = 0 stands for",
        ),
        f(
            id!(age.old_years),
            YEARS,
            0.0,
            150.0,
            "the age t = 1 stands for",
        ),
    ]);
    v.extend(curve!(
        large,
        "large-wrinkle depth (fibres without their own curve)"
    ));
    v.extend(curve!(fine, "fine-wrinkle blend"));
    v.extend(curve!(pores, "pore widening"));
    v.push(f(
        id!(age.pores_young_scale),
        "",
        0.1,
        1.0,
        "pore radius at the young end, relative to pores.radius_mm",
    ));
    v.extend(curve!(furrows, "furrow deepening"));
    v.push(f(
        id!(age.furrows_young_scale),
        "",
        0.0,
        1.0,
        "furrow depth at the young end, relative to furrows.depth",
    ));
    v.extend(curve!(pale, "skin paling and yellowing"));
    v.extend(curve!(spots, "age spots appearing"));
    v.extend(curve!(mottle, "mottled melanin"));
    v.extend(curve!(redness, "redness and thread veins"));
    v.extend(curve!(contrast, "lips and brows fading"));
    v.extend([
        k(
            id!(shape.enabled),
            Kind::Bool,
            "age changes the shape (docs/models.md §13)",
        ),
        f(
            id!(shape.strength),
            "",
            0.0,
            3.0,
            "every shape region's millimetres times this",
        ),
        f(
            id!(shape.brows),
            "",
            0.0,
            3.0,
            "brow descent: its millimetres times this",
        ),
        f(
            id!(shape.lids),
            "",
            0.0,
            3.0,
            "upper lids hooding: its millimetres times this",
        ),
        f(
            id!(shape.bags),
            "",
            0.0,
            3.0,
            "bags under the eyes: its millimetres times this",
        ),
        f(
            id!(shape.tear_trough),
            "",
            0.0,
            3.0,
            "tear trough hollowing: its millimetres times this",
        ),
        f(
            id!(shape.temples),
            "",
            0.0,
            3.0,
            "temples hollowing: its millimetres times this",
        ),
        f(
            id!(shape.cheeks),
            "",
            0.0,
            3.0,
            "cheeks descending over the nasolabial fold: its millimetres times this",
        ),
        f(
            id!(shape.jowls),
            "",
            0.0,
            3.0,
            "jowls below the jaw line: its millimetres times this",
        ),
        f(
            id!(shape.lips),
            "",
            0.0,
            3.0,
            "upper lip lengthening: its millimetres times this",
        ),
        f(
            id!(shape.nose),
            "",
            0.0,
            3.0,
            "nose tip drooping: its millimetres times this",
        ),
        f(
            id!(shape.ears),
            "",
            0.0,
            3.0,
            "earlobes lengthening: its millimetres times this",
        ),
        f(
            id!(shape.neck),
            "",
            0.0,
            3.0,
            "submental laxity: its millimetres times this",
        ),
        k(
            id!(view.pom),
            Kind::Choice(&["linear", "binary", "combined", "normal", "displacement"]),
            "relief: POM linear / binary / combined, normal map only, displaced geometry",
        ),
        i(
            id!(view.linear_steps),
            "",
            1,
            256,
            "POM linear search steps L",
        ),
        i(
            id!(view.binary_steps),
            "",
            0,
            32,
            "POM binary search steps B",
        ),
        f(
            id!(view.disp_scale),
            "UV",
            0.0,
            0.1,
            "POM depth of the full large-wrinkle height (dispScale)",
        ),
        f(
            id!(view.light_yaw_deg),
            "degrees",
            -360.0,
            360.0,
            "light direction around the head",
        ),
        f(
            id!(view.light_pitch_deg),
            "degrees",
            -90.0,
            90.0,
            "light elevation",
        ),
        f(
            id!(view.fill_light),
            "",
            0.0,
            1.0,
            "fill light from the other side, a fraction of the key light",
        ),
        k(
            id!(view.shadows),
            Kind::Bool,
            "the key light's contact shadows (nose, brows, folds, jaw)",
        ),
        f(
            id!(view.camera_yaw_deg),
            "degrees",
            -360.0,
            360.0,
            "camera orbit angle",
        ),
        f(
            id!(view.camera_pitch_deg),
            "degrees",
            -89.0,
            89.0,
            "camera elevation",
        ),
        f(
            id!(view.camera_distance_m),
            "m",
            0.01,
            100.0,
            "camera distance from the head's centre",
        ),
        f(
            id!(view.fov_deg),
            "degrees",
            5.0,
            120.0,
            "vertical field of view",
        ),
        k(id!(view.show_hair), Kind::Bool, "draw the hair"),
        k(
            id!(view.wireframe),
            Kind::Bool,
            "draw the mesh's triangle edges over the skin",
        ),
    ]);
    v
});
