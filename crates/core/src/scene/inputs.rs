//! The inputs of a scene: the mesh, wrinkle files, masks and fine-wrinkle tile it loads
//! from files (or the built-in defaults), and the loaders.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::{FileVersions, WrinkleSource};
use crate::base::arc_key::ArcKey;
use crate::base::error::Error;
use crate::head::fit::Fit;
use crate::head::landmarks::Landmarks;
use crate::head::mesh::Mesh;
use crate::head::mesh::units::Axes;
use crate::layers::wrinkles::wrinkle_file::{self, ParseErrors, WrinkleFile};
use crate::maps::heightmap::HeightMap;
use crate::maps::mask::{HeadImage, Mask};
use crate::project::{AxisChoice, BuiltinMesh, LandmarkSource, Layout, Project};

/// Everything loaded from files (or the built-in defaults), kept until a path changes.
#[derive(Clone, Debug)]
pub(super) struct Inputs {
    mesh_key: (Option<PathBuf>, BuiltinMesh, u64),
    /// The mesh as its file has it, and turned to agesim's axes (`mesh`; the same
    /// allocation when no turn is needed).
    pub(super) raw_mesh: Arc<Mesh>,
    pub(super) mesh: Arc<Mesh>,
    /// The mesh file's axes (`mesh.up`, `mesh.forward`, else from the landmarks, else
    /// found by fitting the template), how they were decided, and what decided them.
    pub(super) axes: Axes,
    pub(super) axes_how: String,
    axes_key: (AxisChoice, AxisChoice, Layout, Option<ArcKey<Landmarks>>),
    /// The skin parts chosen by hand (`mesh.skin_parts`).
    skin_parts: Option<Vec<String>>,
    pub(super) wrinkles_key: Vec<PathBuf>,
    pub(super) wrinkles: Vec<WrinkleSource>,
    /// Whether `wrinkles` came from [`Scene::set_wrinkles`](super::Scene::set_wrinkles)
    /// rather than the files.
    pub(super) wrinkles_edited: bool,
    large_mask_key: (Option<PathBuf>, bool, u64),
    pub(super) large_mask: Option<Arc<Mask>>,
    hair_masks_key: (Option<PathBuf>, Option<PathBuf>, u64, u64),
    pub(super) hair_masks: Option<Arc<(Mask, Mask)>>,
    fine_tile_key: (Option<PathBuf>, u64),
    pub(super) fine_tile: Option<Arc<HeightMap>>,
    landmarks_key: (Option<LandmarkSource>, u64),
    /// The head's landmarks (`mesh.landmarks`), when the project names a file.
    pub(super) landmarks: Option<Arc<Landmarks>>,
    colour_map_key: (Option<PathBuf>, bool, u64),
    /// The head's base colour map (`mesh.colour_map`), when the project names one.
    pub(super) colour_map: Option<Arc<HeadImage>>,
    /// The pictures the mesh file's own material names (read with the mesh).
    pub(super) file_textures: Arc<crate::head::mesh::textures::MeshTextures>,
    normal_map_key: (Option<PathBuf>, bool, u64),
    /// The head's normal map (`mesh.normal_map`), when the project names one.
    pub(super) normal_map: Option<Arc<HeadImage>>,
    /// How the mesh reads the layers (the template's fit).
    pub(super) layout: Arc<HeadLayout>,
    /// Bumped whenever any input above changes (fibre edits included).
    pub(super) generation: u64,
}

impl Inputs {
    /// Whether `self` and `other` hold the same files' contents (the same decoded
    /// allocations): kept as a past state only when they differ.
    pub(super) fn same_files(&self, other: &Inputs) -> bool {
        Arc::ptr_eq(&self.raw_mesh, &other.raw_mesh)
            && opt_ptr_eq(&self.large_mask, &other.large_mask)
            && opt_ptr_eq(&self.hair_masks, &other.hair_masks)
            && opt_ptr_eq(&self.fine_tile, &other.fine_tile)
            && opt_ptr_eq(&self.landmarks, &other.landmarks)
            && opt_ptr_eq(&self.colour_map, &other.colour_map)
            && opt_ptr_eq(&self.normal_map, &other.normal_map)
    }

    pub(super) fn generation_of_fine(&self) -> Option<ArcKey<HeightMap>> {
        self.fine_tile.as_ref().map(ArcKey::of)
    }

    /// Loads what `project` names, reusing the inputs of `kept` (the current state first,
    /// then past ones) whose key — path and [`FileVersions`] version — is unchanged.
    /// Every failing input is reported (wrinkle files with all their diagnostics).
    pub(super) fn load(
        project: &Project,
        versions: &FileVersions,
        kept: &[&Inputs],
        shown: &mut dyn FnMut(&Arc<Mesh>),
    ) -> Result<Self, Error> {
        let version = |p: &Option<PathBuf>| {
            p.as_ref()
                .and_then(|p| versions.get(p))
                .copied()
                .unwrap_or(0)
        };
        let find = |same: &dyn Fn(&Inputs) -> bool| kept.iter().copied().find(|p| same(p));
        let previous = kept.first().copied();
        let mesh_key = (
            project.mesh.path.clone(),
            project.mesh.builtin,
            version(&project.mesh.path),
        );
        let wrinkles_key = project.large.wrinkles.clone();
        let large_mask_key = (
            project.large.mask.clone(),
            project.large.wrinkles.is_empty(),
            version(&project.large.mask),
        );
        let hair_masks_key = (
            project.hair.outer_mask.clone(),
            project.hair.inner_mask.clone(),
            version(&project.hair.outer_mask),
            version(&project.hair.inner_mask),
        );
        let fine_tile_key = (project.fine.tile.clone(), version(&project.fine.tile));
        // The inputs are independent: decoded at once on the pool (the mesh and the
        // masks are most of a bake's start-up). Errors are reported in this fixed order.
        let load_mesh_part = || match find(&|p| p.mesh_key == mesh_key) {
            Some(p) => Ok((p.raw_mesh.clone(), p.file_textures.clone())),
            None => {
                let mesh = load_mesh(project).map(Arc::new)?;
                let textures = match (&project.mesh.path, project.mesh.builtin) {
                    (Some(path), _) => {
                        Arc::new(crate::head::mesh::textures::load_tiled(path, mesh.udim())?)
                    }
                    (None, crate::project::BuiltinMesh::Head) => {
                        crate::head::default::default_head_textures()
                    }
                    (None, _) => Arc::default(),
                };
                Ok((mesh, textures))
            }
        };
        let load_wrinkles_part = || match previous.filter(|p| p.wrinkles_key == wrinkles_key) {
            Some(p) => Ok((p.wrinkles.clone(), p.wrinkles_edited)),
            None => load_wrinkles(&wrinkles_key).map(|w| (w, false)),
        };
        let load_large_mask_part = || match find(&|p| p.large_mask_key == large_mask_key) {
            Some(p) => Ok(p.large_mask.clone()),
            None => load_large_mask(&large_mask_key).map(|m| m.map(Arc::new)),
        };
        let load_hair_part = || match find(&|p| p.hair_masks_key == hair_masks_key) {
            Some(p) => (Ok(p.hair_masks.clone()), Ok(())),
            None => {
                let (outer, inner) = rayon::join(
                    || {
                        load_mask_or(
                            hair_masks_key.0.as_deref(),
                            crate::defaults::HAIR_OUTER_MASK,
                        )
                    },
                    || {
                        load_mask_or(
                            hair_masks_key.1.as_deref(),
                            crate::defaults::HAIR_INNER_MASK,
                        )
                    },
                );
                match (outer, inner) {
                    (Ok(o), Ok(i)) => (Ok(Some(Arc::new((o, i)))), Ok(())),
                    (o, i) => (o.map(|_| None), i.map(|_| ())),
                }
            }
        };
        let load_fine_part = || match find(&|p| p.fine_tile_key == fine_tile_key) {
            Some(p) => Ok(p.fine_tile.clone()),
            None => match &fine_tile_key.0 {
                None => Ok(None),
                Some(path) => Mask::load(path)
                    .and_then(|m| {
                        HeightMap::from_vec(m.width_px(), m.height_px(), m.values().to_vec())
                    })
                    .map(|h| Some(Arc::new(h))),
            },
        };
        let (mesh, ((wrinkles, large_mask), ((hair_masks, inner_error), fine_tile))) =
            rayon::join(load_mesh_part, || {
                rayon::join(
                    || rayon::join(load_wrinkles_part, load_large_mask_part),
                    || rayon::join(load_hair_part, load_fine_part),
                )
            });
        let mut errors: Vec<Error> = Vec::new();
        let mut ok = |r: Result<(), Error>| errors.extend(r.err());
        let (mesh, file_textures) = match mesh.map_err(|e| ok(Err(e))).ok() {
            Some((m, t)) => (Some(m), t),
            None => (None, Arc::default()),
        };
        let (wrinkles, wrinkles_edited) = match wrinkles {
            Ok((w, edited)) => (Some(w), edited),
            Err(e) => {
                ok(Err(e));
                (None, false)
            }
        };
        let large_mask = large_mask.map_err(|e| ok(Err(e))).ok();
        let hair_masks = hair_masks.map_err(|e| ok(Err(e))).ok();
        ok(inner_error);
        let fine_tile = fine_tile.map_err(|e| ok(Err(e))).ok();
        // A small text file (or the project's own points): read after the rest.
        let landmarks_key = (
            project.mesh.landmarks.clone(),
            version(&project.mesh.landmark_file().map(Path::to_path_buf)),
        );
        let landmarks = match find(&|p| p.landmarks_key == landmarks_key) {
            Some(p) => p.landmarks.clone(),
            None => match landmarks_key.0.as_ref().map(load_landmarks).transpose() {
                Ok(l) => l.map(Arc::new),
                Err(e) => {
                    errors.push(e);
                    None
                }
            },
        };
        // The head's pictures: small, read after the rest.
        let mut load_picture =
            |key: &(Option<PathBuf>, bool, u64),
             kept: Option<Option<Arc<HeadImage>>>,
             encoding: crate::maps::mask::Encoding| {
                kept.unwrap_or_else(|| {
                    let path = key.0.as_ref()?;
                    HeadImage::load_as(path, key.1, encoding)
                        .map_err(|e| errors.push(e))
                        .ok()
                        .map(Arc::new)
                })
            };
        let flip = project.mesh.maps_flip_v;
        let colour_map_key = (
            project.mesh.colour_map.clone(),
            flip,
            version(&project.mesh.colour_map),
        );
        let colour_map = load_picture(
            &colour_map_key,
            find(&|p| p.colour_map_key == colour_map_key).map(|p| p.colour_map.clone()),
            crate::maps::mask::Encoding::Colour,
        );
        let normal_map_key = (
            project.mesh.normal_map.clone(),
            flip,
            version(&project.mesh.normal_map),
        );
        let normal_map = load_picture(
            &normal_map_key,
            find(&|p| p.normal_map_key == normal_map_key).map(|p| p.normal_map.clone()),
            crate::maps::mask::Encoding::Data,
        );
        match (mesh, wrinkles, large_mask, hair_masks, fine_tile) {
            (
                Some(raw_mesh),
                Some(wrinkles),
                Some(large_mask),
                Some(hair_masks),
                Some(fine_tile),
            ) if errors.is_empty() => {
                let axes_key = (
                    project.mesh.up,
                    project.mesh.forward,
                    project.mesh.layout,
                    landmarks.as_ref().map(ArcKey::of),
                );
                // Finding the axes by fitting is not free: kept while the mesh and what
                // decides them are the same.
                let (axes, axes_how) = match find(&|p| {
                    Arc::ptr_eq(&p.raw_mesh, &raw_mesh) && p.axes_key == axes_key
                }) {
                    Some(p) => (p.axes, p.axes_how.clone()),
                    None => axes_of(project, landmarks.as_deref(), &raw_mesh),
                };
                let skin_parts = project.mesh.skin_parts.clone();
                let mesh = match find(&|p| {
                    Arc::ptr_eq(&p.raw_mesh, &raw_mesh)
                        && p.axes == axes
                        && p.skin_parts == skin_parts
                }) {
                    Some(p) => p.mesh.clone(),
                    None => {
                        let turned = match axes.to_standard() {
                            Some(r) if axes != Axes::STANDARD => Arc::new(raw_mesh.rotated(r)),
                            _ => raw_mesh.clone(),
                        };
                        match &skin_parts {
                            None => turned,
                            Some(names) => {
                                let (chosen, unknown) = turned.with_skin_parts(names);
                                if !unknown.is_empty() {
                                    let parts: Vec<&str> =
                                        turned.parts().iter().map(|p| p.name.as_str()).collect();
                                    return Err(Error::Project {
                                        source_name: "project".into(),
                                        message: format!(
                                            "mesh.skin_parts: no part of the mesh is named like {} (its parts: {})",
                                            unknown.join(", "),
                                            parts.join("; ")
                                        ),
                                    });
                                }
                                Arc::new(chosen)
                            }
                        }
                    }
                };
                if kept.iter().all(|p| !Arc::ptr_eq(&p.mesh, &mesh)) {
                    shown(&mesh);
                }
                let layout = match find(&|p| {
                    Arc::ptr_eq(&p.mesh, &mesh)
                        && opt_ptr_eq(&p.landmarks, &landmarks)
                        && p.layout.choice == project.mesh.layout
                }) {
                    Some(p) => p.layout.clone(),
                    None => Arc::new(HeadLayout::of(project, &mesh, axes, landmarks.as_deref())?),
                };
                let generation = previous.map_or(0, |p| p.generation)
                    + u64::from(previous.is_none_or(|p| p.wrinkles != wrinkles));
                Ok(Self {
                    mesh_key,
                    raw_mesh,
                    mesh,
                    axes,
                    axes_how,
                    axes_key,
                    skin_parts,
                    wrinkles_key,
                    wrinkles,
                    wrinkles_edited,
                    large_mask_key,
                    large_mask,
                    hair_masks_key,
                    hair_masks,
                    fine_tile_key,
                    fine_tile,
                    landmarks_key,
                    landmarks,
                    colour_map_key,
                    colour_map,
                    file_textures,
                    normal_map_key,
                    normal_map,
                    layout,
                    generation,
                })
            }
            _ if errors.len() == 1 => Err(errors.remove(0)),
            _ => Err(Error::Inputs(
                errors.iter().map(ToString::to_string).collect(),
            )),
        }
    }
}

fn opt_ptr_eq<T>(a: &Option<Arc<T>>, b: &Option<Arc<T>>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => Arc::ptr_eq(a, b),
        (None, None) => true,
        _ => false,
    }
}

/// How a scene's mesh reads the layers authored on the template (`mesh.layout`).
#[derive(Clone, Debug)]
pub struct HeadLayout {
    /// The project's choice.
    pub choice: Layout,
    /// The template fitted to the head; `None` = the layers are read at the head's own
    /// UVs (a built-in mesh, `own-uvs`, or no landmarks found).
    pub fit: Option<Arc<Fit>>,
    /// The landmarks the fit used, in the scene's coordinates (+Y up, +Z forward): the
    /// project's file's, or found ([`crate::head::fit::auto`]).
    pub landmarks: Option<Arc<Landmarks>>,
    /// Whether `landmarks` were found automatically (not read from a file).
    pub found: bool,
    /// The head is a face only (a mask: no ears, scalp or neck,
    /// [`crate::head::fit::auto::face_only`]): the layers that have no place on it (the
    /// hair) are left out.
    pub face_only: bool,
    /// How it was decided, for reports.
    pub how: String,
    /// How much further than the template's the lips deflate with age, by how far they
    /// stand out ([`crate::layers::shape::anatomy::lip_fullness`]); 1 unfitted.
    pub lip_fullness: f32,
    /// How far its eyes are open, mm on the head scaled to the template's size
    /// ([`crate::layers::shape::anatomy::eye_opening`]); `None` unfitted or closed.
    pub eye_opening_mm: Option<f32>,
    /// How much further down than the template's its lower lip's red reaches where the
    /// fit lays it on the template ([`lower_lip_reach`]); 0 unfitted.
    pub lower_lip_reach: f32,
}

/// The largest median distance (template mm) between the template aligned by the
/// automatic search and the head for its landmarks to be used: beyond, the "head" is
/// not one the template fits (a flat patch, a body).
pub const AUTO_FIT_MAX_MEDIAN_MM: f32 = 6.0;

impl HeadLayout {
    fn own(choice: Layout, how: impl Into<String>) -> Self {
        Self {
            choice,
            fit: None,
            landmarks: None,
            found: false,
            face_only: false,
            how: how.into(),
            lip_fullness: 1.0,
            eye_opening_mm: None,
            lower_lip_reach: 0.0,
        }
    }

    /// Fits the template to `mesh` (already turned to agesim's axes by `axes`), from the
    /// project's landmarks (file coordinates) or found ones. When the fit fails (too few
    /// landmarks, found ones that do not fit) the layers are read at the head's own UVs,
    /// and `how` says why; and a face only says what is left out.
    fn of(
        project: &Project,
        mesh: &Arc<Mesh>,
        axes: Axes,
        file_landmarks: Option<&Landmarks>,
    ) -> Result<Self, Error> {
        let mut layout = Self::fitted(project, mesh, axes, file_landmarks)?;
        if project.mesh.path.is_some() && crate::head::fit::auto::face_only(mesh).is_some() {
            layout.face_only = true;
            layout
                .how
                .push_str("; a face only (no ears, scalp or neck): no hair, and no neck to age");
        }
        Ok(layout)
    }

    fn fitted(
        project: &Project,
        mesh: &Arc<Mesh>,
        axes: Axes,
        file_landmarks: Option<&Landmarks>,
    ) -> Result<Self, Error> {
        let choice = project.mesh.layout;
        if project.mesh.path.is_none() {
            return Ok(Self::own(choice, "the built-in mesh's own UVs"));
        }
        if choice == Layout::OwnUvs {
            return Ok(Self::own(
                choice,
                "the head's own UVs (mesh.layout = own-uvs)",
            ));
        }
        let template = crate::head::fit::template();
        let rotation = axes.to_standard().unwrap_or(glam::Mat3::IDENTITY);
        if let Some(file) = file_landmarks {
            let mut turned = Landmarks::default();
            for name in crate::head::landmarks::NAMES {
                if let Some(p) = file.get(name) {
                    turned.set(name, rotation * p)?;
                }
            }
            // A file too thin to fit (two eye corners for the units) still gives the
            // units: the layers are then read at the head's own UVs, and the report says
            // why.
            return Ok(match crate::head::fit::fit(mesh, &turned, template) {
                Ok(fit) => Self {
                    choice,
                    how: format!("the template fitted by the landmark file: {}", fit.report),
                    lip_fullness: lip_fullness(mesh, &turned, &fit),
                    eye_opening_mm: eye_opening_mm(mesh, &turned, &fit),
                    lower_lip_reach: lower_lip_reach(mesh, &turned, &fit),
                    fit: Some(Arc::new(fit)),
                    landmarks: Some(Arc::new(turned)),
                    found: false,
                    face_only: false,
                },
                Err(e) => Self {
                    landmarks: Some(Arc::new(turned)),
                    ..Self::own(choice, format!("the head's own UVs: {e}"))
                },
            });
        }
        let guess = crate::head::mesh::units::detect(&mesh.bounds(), None).metres_per_unit;
        let guess = project.mesh.metres_per_unit.unwrap_or(guess);
        let found = match crate::head::fit::auto::landmarks(mesh, template, guess) {
            Ok(f) => f,
            Err(e) => return Ok(Self::own(choice, format!("the head's own UVs: {e}"))),
        };
        if found.median_distance_mm > AUTO_FIT_MAX_MEDIAN_MM {
            return Ok(Self::own(
                choice,
                format!(
                    "the head's own UVs: no head shape found (the template stays {:.1} mm from it, over {AUTO_FIT_MAX_MEDIAN_MM} mm); give landmarks (mesh.landmarks) to fit it",
                    found.median_distance_mm
                ),
            ));
        }
        match crate::head::fit::fit(mesh, &found.landmarks, template) {
            Ok(fit) => Ok(Self {
                choice,
                how: format!(
                    "the template fitted by landmarks found automatically (template {:.1} mm from the head): {}",
                    found.median_distance_mm, fit.report
                ),
                lip_fullness: lip_fullness(mesh, &found.landmarks, &fit),
                eye_opening_mm: eye_opening_mm(mesh, &found.landmarks, &fit),
                lower_lip_reach: lower_lip_reach(mesh, &found.landmarks, &fit),
                fit: Some(Arc::new(fit)),
                landmarks: Some(Arc::new(found.landmarks)),
                found: true,
                face_only: false,
            }),
            Err(e) => Ok(Self::own(choice, format!("the head's own UVs: {e}"))),
        }
    }
}

/// How much further than the template's this head's lips deflate
/// ([`crate::layers::shape::anatomy`]): its lips' prominence, scaled to the template's
/// size by the fit's similarity, against the template's.
fn lip_fullness(mesh: &Mesh, landmarks: &Landmarks, fit: &crate::head::fit::Fit) -> f32 {
    use crate::layers::shape::anatomy;
    let head = anatomy::lip_prominence(mesh.positions(), &mesh.skin_indices(), landmarks);
    match (head, anatomy::template_lip_prominence()) {
        (Some(head), Some(template)) => {
            anatomy::lip_fullness(head * fit.similarity.scale, template)
        }
        _ => 1.0,
    }
}

/// How much further down than the template's this head's lower lip's red reaches where
/// the fit lays it on the template: how much further below the template's mouth the fit
/// lays the head's mentolabial sulcus
/// ([`crate::layers::shape::anatomy::mentolabial_sulcus`]; the template point of the skin
/// vertex nearest it) than the template's own sulcus lies, in the face frame's units
/// ([`crate::head::frame::Regions::below_mouth`]); from 0 (no further: the lips' regions
/// as they are) to [`LOWER_LIP_REACH_MAX`]. A full lower lip's red the fit lays partly
/// over the template's skin below its red, where the lips' regions did not reach.
fn lower_lip_reach(mesh: &Mesh, landmarks: &Landmarks, fit: &crate::head::fit::Fit) -> f32 {
    use crate::layers::shape::anatomy::mentolabial_sulcus;
    let (Some(regions), template) = (
        crate::head::frame::Regions::template(),
        crate::head::fit::template(),
    ) else {
        return 0.0;
    };
    static TEMPLATE: std::sync::OnceLock<Option<f32>> = std::sync::OnceLock::new();
    let own = *TEMPLATE.get_or_init(|| {
        let m = &template.mesh;
        mentolabial_sulcus(m.positions(), &m.skin_indices(), &template.landmarks)
            .map(|p| regions.below_mouth(p))
    });
    let skin = mesh.skin_indices();
    let head = mentolabial_sulcus(mesh.positions(), &skin, landmarks).and_then(|sulcus| {
        let nearest = skin.iter().map(|&i| i as usize).min_by(|&a, &b| {
            let d = |v: usize| mesh.positions()[v].distance_squared(sulcus);
            d(a).total_cmp(&d(b))
        })?;
        fit.template_point.get(nearest).copied().flatten()
    });
    match (head, own) {
        (Some(t), Some(own)) => (regions.below_mouth(t) - own).clamp(0.0, LOWER_LIP_REACH_MAX),
        _ => 0.0,
    }
}

/// The farthest a lower lip's red reaches past the template's ([`lower_lip_reach`]), in
/// the face frame's units (half the outer eye corners' distance: 0.3 is about 14 mm).
pub const LOWER_LIP_REACH_MAX: f32 = 0.3;

/// How far this head's eyes are open ([`crate::layers::shape::anatomy::eye_opening`]),
/// mm once the fit's similarity has scaled it to the template's size.
fn eye_opening_mm(mesh: &Mesh, landmarks: &Landmarks, fit: &crate::head::fit::Fit) -> Option<f32> {
    crate::layers::shape::anatomy::eye_opening(mesh.positions(), &mesh.skin_indices(), landmarks)
        .map(|o| o * fit.similarity.scale * 1000.0)
}

/// A mesh file's axes: the project's where it names them, else the landmarks', else
/// agesim's own. The built-in meshes are agesim's own.
fn axes_of(project: &Project, landmarks: Option<&Landmarks>, mesh: &Mesh) -> (Axes, String) {
    if project.mesh.path.is_none() {
        return (Axes::STANDARD, "agesim's own: a built-in mesh".into());
    }
    let (up, forward) = (project.mesh.up.axis(), project.mesh.forward.axis());
    if let (Some(up), Some(forward)) = (up, forward) {
        return (Axes { up, forward }, "set in the project".into());
    }
    if let Some(detected) = landmarks.and_then(crate::head::mesh::units::detect_axes) {
        let axes = Axes {
            up: up.unwrap_or(detected.up),
            forward: forward.unwrap_or(detected.forward),
        };
        return (axes, "from the landmarks".into());
    }
    // A face only (a mask) has no cranium to fit: it faces the way its surface does, up
    // assumed +Y (or +Z for a face looking along Y).
    if up.is_none()
        && forward.is_none()
        && let Some(facing) = crate::head::fit::auto::face_only(mesh)
        && let Some(forward) = crate::head::mesh::units::Axis::nearest_to(facing)
    {
        use crate::head::mesh::units::Axis;
        let up = if matches!(forward, Axis::PosY | Axis::NegY) {
            Axis::PosZ
        } else {
            Axis::PosY
        };
        return (
            Axes { up, forward },
            format!(
                "a face only: it faces {}, up assumed {}",
                forward.name(),
                up.name()
            ),
        );
    }
    // No landmarks to read them from: the orientation the template fits best.
    if up.is_none() && forward.is_none() && project.mesh.layout == Layout::Template {
        let guess = crate::head::mesh::units::detect(&mesh.bounds(), None).metres_per_unit;
        let guess = project.mesh.metres_per_unit.unwrap_or(guess);
        if let Some((axes, mm)) =
            crate::head::fit::auto::axes(mesh, crate::head::fit::template(), guess, AXES_GOOD_MM)
            && mm <= AUTO_FIT_MAX_MEDIAN_MM
        {
            return (
                axes,
                format!("found by fitting the template ({mm:.1} mm from the head)"),
            );
        }
    }
    let axes = Axes {
        up: up.unwrap_or(Axes::STANDARD.up),
        forward: forward.unwrap_or(Axes::STANDARD.forward),
    };
    (
        axes,
        "assumed: no landmarks of the chin, brow, eyes and nose, and no orientation the template fits".into(),
    )
}

/// A head the template fits within this (median, mm) in agesim's own orientation is
/// taken as upright and facing +Z without trying the other 23.
const AXES_GOOD_MM: f32 = 5.0;

fn load_mesh(project: &Project) -> Result<Mesh, Error> {
    match (&project.mesh.path, project.mesh.builtin) {
        (Some(path), _) => Mesh::load(path),
        (None, BuiltinMesh::Head) => Ok(crate::head::default::default_head()),
        (None, BuiltinMesh::SkinPatch) => Ok(crate::head::default::skin_patch()),
    }
}

/// The wrinkle files at `paths` (the built-in defaults when empty), every diagnostic of
/// every file reported together.
pub fn load_wrinkles(paths: &[PathBuf]) -> Result<Vec<WrinkleSource>, Error> {
    let mut loaded = Vec::new();
    let mut diagnostics = Vec::new();
    let mut push = |name: String,
                    path: Option<PathBuf>,
                    result: Result<WrinkleFile, ParseErrors>| {
        match result {
            Ok(file) => loaded.push(WrinkleSource { name, path, file }),
            Err(errors) => diagnostics.extend(errors.0),
        }
    };
    if paths.is_empty() {
        for (name, text) in crate::defaults::WRINKLE_FILES {
            push(
                name.to_string(),
                None,
                wrinkle_file::parse(text, Path::new(name)),
            );
        }
    } else {
        for path in paths {
            let bytes =
                crate::base::limits::read_file(path, crate::base::limits::MAX_TEXT_FILE_BYTES)?;
            push(
                path.display().to_string(),
                Some(path.clone()),
                wrinkle_file::parse_bytes(&bytes, path),
            );
        }
    }
    if diagnostics.is_empty() {
        Ok(loaded)
    } else {
        Err(Error::WrinkleFile(ParseErrors(diagnostics)))
    }
}

/// The landmarks of `mesh.landmarks`: its file's, or the project's own points.
fn load_landmarks(source: &LandmarkSource) -> Result<Landmarks, Error> {
    match source {
        LandmarkSource::File(path) => Landmarks::load(path),
        LandmarkSource::Points(points) => {
            let object = points
                .iter()
                .map(|(name, p)| (name.clone(), serde_json::Value::from(p.to_vec())))
                .collect();
            Landmarks::from_points(&object).map_err(|message| Error::Project {
                source_name: "project".into(),
                message: format!("mesh.landmarks: {message}"),
            })
        }
    }
}

/// The large-wrinkle mask: the named one, or the default head's when the default wrinkle
/// files are used, or none.
fn load_large_mask(key: &(Option<PathBuf>, bool, u64)) -> Result<Option<Mask>, Error> {
    match key {
        (Some(path), ..) => Mask::load(path).map(Some),
        (None, true, _) => {
            let (name, bytes) = crate::defaults::WRINKLE_MASK;
            Mask::decode(bytes, Path::new(name)).map(Some)
        }
        (None, false, _) => Ok(None),
    }
}

fn load_mask_or(path: Option<&Path>, default: (&str, &[u8])) -> Result<Mask, Error> {
    match path {
        Some(p) => Mask::load(p),
        None => Mask::decode(default.1, Path::new(default.0)),
    }
}
