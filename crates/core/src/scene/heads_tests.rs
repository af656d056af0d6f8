//! The layers land where they belong on heads that are not the template, measured in 3D
//! against each head's landmarks (issue "any head").
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::PathBuf;

use glam::{Vec2, Vec3};

use super::*;

fn heads_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/heads")
}

fn wrinkle_file(region: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/wrinkles")
        .join(format!("{region}.wrk"))
}

/// The 3D point at each texel centre of `mesh`'s UV layout (`None` off every island).
fn uv_positions(mesh: &Mesh, size: u32) -> Vec<Option<Vec3>> {
    let n = size as usize;
    let mut out = vec![None; n * n];
    let (p, uv) = (mesh.positions(), mesh.uvs());
    let idx = mesh.skin_indices();
    for t in idx.chunks_exact(3) {
        let (a, b, c) = (t[0] as usize, t[1] as usize, t[2] as usize);
        let px = |u: Vec2| Vec2::new(u.x * size as f32, (1.0 - u.y) * size as f32);
        let (pa, pb, pc) = (px(uv[a]), px(uv[b]), px(uv[c]));
        let area = (pb - pa).perp_dot(pc - pa);
        if area.abs() < 1e-12 {
            continue;
        }
        let lo = pa.min(pb).min(pc).floor().max(Vec2::ZERO);
        let hi = pa.max(pb).max(pc).ceil().min(Vec2::splat(size as f32));
        for y in lo.y as usize..hi.y as usize {
            for x in lo.x as usize..hi.x as usize {
                let q = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                let w0 = (pc - pb).perp_dot(q - pb) / area;
                let w1 = (pa - pc).perp_dot(q - pc) / area;
                let w2 = 1.0 - w0 - w1;
                if w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0 {
                    out[y * n + x] = Some(p[a] * w0 + p[b] * w1 + p[c] * w2);
                }
            }
        }
    }
    out
}

/// A check of a region's wrinkle points on the subject's right and left.
type SideTest<'a> = dyn Fn(&[Vec3], &[Vec3]) -> Result<(), String> + 'a;

struct Head {
    name: &'static str,
    file: &'static str,
}

const HEADS: [Head; 3] = [
    // The template itself, read at its own UVs: its layout checked against its landmarks.
    Head {
        name: "default head",
        file: "",
    },
    Head {
        name: "lee-perry-smith",
        file: "LeePerrySmith.glb",
    },
    Head {
        name: "makehuman",
        file: "mh_head.obj",
    },
];

fn reference_landmarks(head: &Head) -> crate::landmarks::Landmarks {
    if head.file.is_empty() {
        crate::fit::template().landmarks.clone()
    } else {
        crate::landmarks::Landmarks::load(&heads_dir().join(head.name).join("landmarks.json"))
            .unwrap()
    }
}

fn project_for(head: &Head, landmarks: bool) -> Project {
    let dir = heads_dir().join(head.name);
    let mut p = Project::default();
    p.pores.enabled = false;
    p.furrows.enabled = false;
    p.noise.strength = 0.0;
    if head.file.is_empty() {
        return p;
    }
    p.mesh.path = Some(dir.join(head.file));
    p.mesh.metres_per_unit = None;
    p.mesh.landmarks = landmarks.then(|| dir.join("landmarks.json"));
    p
}

/// Where a region's wrinkles are: the 3D points of the texels at over half the map's
/// peak, split into the subject's right (x below the face's midline) and left.
fn wrinkle_points(scene: &mut Scene, size: u32) -> Vec<Vec3> {
    scene
        .bake(&BakeRequest::maps(size, 1.0, false), &CancelToken::never())
        .unwrap();
    let map = &scene.large().unwrap().height;
    let peak = map.data().iter().fold(0.0f32, |m, &h| m.max(h.abs()));
    assert!(peak > 0.0, "no wrinkle baked");
    let points = uv_positions(scene.mesh(), size);
    map.data()
        .iter()
        .zip(&points)
        .filter(|(h, p)| h.abs() > 0.5 * peak && p.is_some())
        .map(|(_, p)| p.unwrap())
        .collect()
}

fn centroid(points: &[Vec3]) -> Vec3 {
    points.iter().sum::<Vec3>() / points.len().max(1) as f32
}

#[test]
fn every_region_lands_where_it_belongs_on_heads_that_are_not_the_template() {
    let size = 512;
    for head in &HEADS {
        for with_landmarks in [true, false] {
            let mut project = project_for(head, with_landmarks);
            // The head's own landmarks (hand-placed) are the reference in both cases.
            let l = reference_landmarks(head);
            let g = |n: &str| l.get(n).unwrap();
            let eyes = l.exocanthion_distance().unwrap();
            let mid_x = (g("exocanthion_r").x + g("exocanthion_l").x) * 0.5;
            let what = format!(
                "{} ({} landmarks)",
                head.name,
                if with_landmarks {
                    "hand-placed"
                } else {
                    "automatic"
                }
            );
            let mut check = |region: &str, test: &SideTest<'_>| {
                project.large.wrinkles = vec![wrinkle_file(region)];
                let mut scene = Scene::new(project.clone()).unwrap();
                assert!(
                    scene.layout().fit.is_some() || head.file.is_empty(),
                    "{what}: {}",
                    scene.layout().how
                );
                let points = wrinkle_points(&mut scene, size);
                let (right, left): (Vec<Vec3>, Vec<Vec3>) =
                    points.iter().partition(|p| p.x < mid_x);
                if let Err(e) = test(&right, &left) {
                    panic!(
                        "{what}, {region}: {e} (right {:?}, left {:?}, {} texels)",
                        centroid(&right),
                        centroid(&left),
                        points.len()
                    );
                }
            };
            let near = |p: Vec3, q: Vec3, r: f32, what: &str| {
                if p.distance(q) <= r * eyes {
                    Ok(())
                } else {
                    Err(format!(
                        "{what}: {:.2} × the eye distance away",
                        p.distance(q) / eyes
                    ))
                }
            };
            check("forehead", &|r, l| {
                let c = centroid(&[r, l].concat());
                if c.y <= g("glabella").y {
                    return Err("not above the brows".into());
                }
                if (c.x - mid_x).abs() > 0.25 * eyes {
                    return Err("not over the middle of the forehead".into());
                }
                near(c, g("glabella"), 0.9, "the forehead lines and the glabella")
            });
            check("crows-feet", &|r, l| {
                near(centroid(r), g("exocanthion_r"), 0.35, "right crow's feet")?;
                near(centroid(l), g("exocanthion_l"), 0.35, "left crow's feet")
            });
            check("nasolabial", &|r, l| {
                for (side, pts) in [("r", r), ("l", l)] {
                    let c = centroid(pts);
                    let (wing, corner) =
                        (g(&format!("alare_{side}")), g(&format!("cheilion_{side}")));
                    let between = (wing + corner) * 0.5;
                    near(
                        c,
                        between,
                        0.3,
                        &format!("nasolabial {side} from between nose wing and mouth corner"),
                    )?;
                }
                Ok(())
            });
            check("marionette", &|r, l| {
                for (side, pts) in [("r", r), ("l", l)] {
                    let c = centroid(pts);
                    let corner = g(&format!("cheilion_{side}"));
                    if c.y >= corner.y {
                        return Err(format!("marionette {side} not below the mouth corner"));
                    }
                    near(
                        c,
                        corner,
                        0.45,
                        &format!("marionette {side} from the mouth corner"),
                    )?;
                }
                Ok(())
            });
            check("neck", &|r, l| {
                let c = centroid(&[r, l].concat());
                if c.y >= g("pogonion").y {
                    return Err("the neck lines are not below the chin".into());
                }
                Ok(())
            });
        }
    }
}

#[test]
fn no_hair_grows_on_the_face_of_heads_that_are_not_the_template() {
    for head in &HEADS {
        let mut project = project_for(head, true);
        project.large.enabled = false;
        let mut scene = Scene::new(project).unwrap();
        let mut request = BakeRequest::preview(0.0);
        request.large_size_px = 64;
        request.micro_size_px = 64;
        scene.bake(&request, &CancelToken::never()).unwrap();
        let hair = scene.hair().unwrap();
        assert!(hair.len() > 1000, "{}: {} hairs", head.name, hair.len());
        let l = match &scene.layout().landmarks {
            Some(l) => (**l).clone(),
            None => reference_landmarks(head),
        };
        let eyes = l.exocanthion_distance().unwrap();
        for name in [
            "pronasale",
            "exocanthion_r",
            "exocanthion_l",
            "cheilion_r",
            "cheilion_l",
            "pogonion",
            "subnasale",
        ] {
            let p = l.get(name).unwrap();
            let on_face = hair
                .instances()
                .iter()
                .filter(|h| h.position().distance(p) < 0.45 * eyes)
                .count();
            assert_eq!(on_face, 0, "{}: {on_face} hairs near {name}", head.name);
        }
        // And the scalp has hair: some roots above the brows, behind the forehead.
        let top = l.get("glabella").unwrap().y + 0.5 * eyes;
        assert!(
            hair.instances()
                .iter()
                .filter(|h| h.position().y > top)
                .count()
                > hair.len() / 4,
            "{}: the scalp is bald",
            head.name
        );
    }
}
