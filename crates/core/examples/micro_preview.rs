#![allow(clippy::unwrap_used, clippy::expect_used)]
use agesim_core::{micro::MicroRelief, normal_map, project::Project};
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mut p = if args[1] == "-" {
        Project::default()
    } else {
        Project::load(args[1].as_ref()).unwrap()
    };
    let size: u32 = args[2].parse().unwrap();
    let out = std::path::Path::new(&args[3]);
    for kv in &args[4..] {
        let (k, v) = kv.split_once('=').unwrap();
        p = p.set(k, v).unwrap();
    }
    let r = MicroRelief::new(&p).unwrap();
    if std::env::var("TIMING").is_ok() {
        use agesim_core::micro::bake::Parts;
        for parts in [
            Parts {
                features: true,
                noise: true,
            },
            Parts {
                features: true,
                noise: false,
            },
            Parts {
                features: false,
                noise: true,
            },
            Parts {
                features: false,
                noise: false,
            },
        ] {
            let mut v = Vec::new();
            for _ in 0..5 {
                v.push(r.bake_parts(size, parts).unwrap().1.relief_ms);
            }
            eprintln!("{parts:?} {v:.1?}");
        }
    }
    let (map, t) = r.bake(size).unwrap();
    eprintln!(
        "{t:?} pores {} furrows {} range {:?}",
        r.pores().len(),
        r.furrows().len(),
        map.min_max()
    );
    agesim_core::export::write_height_png16(&out.join("height.png"), &map).unwrap();
    let s = normal_map::NormalSettings {
        strength: p.normal.strength,
        tiling: p.tile,
        ..Default::default()
    };
    let rgb = normal_map::encode_rgb8(&map, &s).unwrap();
    agesim_core::export::write_rgb8_png(&out.join("normal.png"), size, size, &rgb).unwrap();
}
#[allow(dead_code)]
fn unused() {}
