//! The shaders' helpers and their CPU twins agree. `shaders/common.wgsl` (what skin.wgsl and
//! hair.wgsl share) is wrapped in compute shaders and run on the GPU over many inputs; each
//! result is compared with the engine's own function:
//! - the octahedral packing: the hair instance's direction, packed on the CPU as snorm16
//!   (`layers::hair::oct_encode`), decoded by the shader as the CPU decodes it; and the
//!   shader's encoding read back by the CPU's decoding;
//! - the gray fraction of a hair (`layers::hair::gray_fraction`), both ramps;
//! - how whole a hair is before it goes (`layers::hair::hair_whole`);
//! - the cavity occlusion (`output::compose::cavity`, the GLB's occlusion texture), and the
//!   cavity and crease-roughness constants, read from the shader by naga;
//! - a scalp hair's strand (`layers::hair::strand`: its curve, its coil and its length),
//!   what the GLB's hair is made of.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod common;

use agesim_core::layers::hair::strand;
use agesim_core::layers::hair::{GrayingRamp, gray_fraction, hair_whole, oct_decode, oct_encode};
use agesim_core::output::compose;
use agesim_render::shaders;
use common::gpu_or_skip;
use glam::Vec3;
use wgpu::util::DeviceExt as _;

/// The entry points wrapped round common.wgsl: each reads one vec4 and writes one.
const HARNESS: &str = r#"
@group(0) @binding(0) var<storage, read> inputs: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> outputs: array<vec4<f32>>;

@compute @workgroup_size(64)
fn cs_oct_decode(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&inputs) {
        outputs[id.x] = vec4<f32>(oct_decode(inputs[id.x].xy), 0.0);
    }
}

@compute @workgroup_size(64)
fn cs_oct_encode(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&inputs) {
        outputs[id.x] = vec4<f32>(oct_encode(inputs[id.x].xyz), 0.0, 0.0);
    }
}

@compute @workgroup_size(64)
fn cs_gray(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&inputs) {
        let x = inputs[id.x];
        outputs[id.x] = vec4<f32>(gray_fraction(x.x, x.y, x.z > 0.5), 0.0, 0.0, 0.0);
    }
}

@compute @workgroup_size(64)
fn cs_whole(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&inputs) {
        let x = inputs[id.x];
        outputs[id.x] = vec4<f32>(hair_whole(x.x, x.y), 0.0, 0.0, 0.0);
    }
}

@compute @workgroup_size(64)
fn cs_cavity(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&inputs) {
        let x = inputs[id.x];
        outputs[id.x] = vec4<f32>(cavity_loss(x.x, x.y), 0.0, 0.0, 0.0);
    }
}

// A strand's point: three vec4 in per case (root, len; dir, random; curl, droop, unit,
// s), the coiled point and tangent's x out in the first third of the outputs, the
// tangent and the length in the second.
@compute @workgroup_size(64)
fn cs_strand(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = arrayLength(&inputs) / 3u;
    if id.x < n {
        let a = inputs[3u * id.x];
        let b = inputs[3u * id.x + 1u];
        let c = inputs[3u * id.x + 2u];
        let len = strand_length(a.w, 0.8, b.w, c.x, 0.6);
        let curve = hair_curve(a.xyz, b.xyz, len, b.w, c.x, c.y, c.z);
        var p = curve_point(curve, c.w);
        var t = curve_tangent(curve, c.w);
        if c.x > 0.0 {
            let coil = coiled(p, t, len, c.w, b.w, c.x);
            p = coil.p;
            t = coil.tangent;
        }
        outputs[id.x] = vec4<f32>(p, 0.0);
        outputs[n + id.x] = vec4<f32>(t, len);
    }
}
"#;

/// Runs `entry` of common.wgsl + [`HARNESS`] over `inputs`, one vec4 out per vec4 in.
fn run(gpu: &agesim_render::Gpu, entry: &str, inputs: &[[f32; 4]]) -> Vec<[f32; 4]> {
    let source = format!("{}{HARNESS}", shaders::COMMON_WGSL);
    let device = &gpu.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("twins"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(entry),
        layout: None,
        module: &module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    });
    let bytes = (inputs.len() * 16) as u64;
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("twins in"),
        contents: bytemuck::cast_slice(inputs),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("twins out"),
        size: bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("twins readback"),
        size: bytes,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("twins"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: input.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: output.as_entire_binding(),
            },
        ],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("twins"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups((inputs.len() as u32).div_ceil(64), 1, 1);
    }
    encoder.copy_buffer_to_buffer(&output, 0, &readback, 0, bytes);
    let submission = gpu.queue.submit([encoder.finish()]);
    let slice = readback.slice(..);
    let (sender, receiver) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| drop(sender.send(r)));
    device
        .poll(wgpu::PollType::Wait {
            submission_index: Some(submission),
            timeout: None,
        })
        .unwrap();
    receiver.recv().unwrap().unwrap();
    let data = slice.get_mapped_range().unwrap();
    bytemuck::cast_slice::<u8, [f32; 4]>(&data).to_vec()
}

/// Unit vectors over the whole sphere (a Fibonacci spiral), the axes and the octahedron's
/// folds, where the packing changes branch.
fn directions() -> Vec<Vec3> {
    let n = 4000;
    let mut out: Vec<Vec3> = (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let a = i as f32 * 2.399_963;
            Vec3::new(r * a.cos(), r * a.sin(), z)
        })
        .collect();
    for v in [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z] {
        out.push(v);
    }
    for x in [-1.0f32, -0.5, 0.0, 0.5, 1.0] {
        for y in [-1.0f32, -0.5, 0.0, 0.5, 1.0] {
            for z in [-0.3f32, -1e-4, 0.0, 1e-4] {
                let v = Vec3::new(x, y, z);
                if v.length() > 0.1 {
                    out.push(v.normalize());
                }
            }
        }
    }
    out
}

#[test]
fn the_hair_shader_decodes_the_cpu_packed_direction_as_the_cpu_does() {
    let Some(gpu) = gpu_or_skip("twins: octahedral decode") else {
        return;
    };
    let dirs = directions();
    // What the vertex fetch of a snorm16 pair gives the shader: max(v / 32767, −1).
    let packed: Vec<[i16; 2]> = dirs.iter().map(|&d| oct_encode(d)).collect();
    let inputs: Vec<[f32; 4]> = packed
        .iter()
        .map(|e| {
            let f = |v: i16| (v as f32 / 32767.0).max(-1.0);
            [f(e[0]), f(e[1]), 0.0, 0.0]
        })
        .collect();
    let out = run(&gpu, "cs_oct_decode", &inputs);
    let mut worst_twin: f32 = 0.0;
    let mut worst_dir: f32 = 0.0;
    for ((e, d), o) in packed.iter().zip(&dirs).zip(&out) {
        let gpu = Vec3::new(o[0], o[1], o[2]);
        worst_twin = worst_twin.max((gpu - oct_decode(*e)).abs().max_element());
        worst_dir = worst_dir.max(gpu.cross(*d).length());
    }
    assert!(
        worst_twin < 1e-5,
        "GPU and CPU decodes differ by {worst_twin}"
    );
    assert!(
        worst_dir < 1e-4,
        "a decoded direction is off by {worst_dir} rad"
    );
}

#[test]
fn the_shader_encoding_reads_back_through_the_cpu_decoding() {
    let Some(gpu) = gpu_or_skip("twins: octahedral encode") else {
        return;
    };
    let dirs = directions();
    let inputs: Vec<[f32; 4]> = dirs.iter().map(|d| [d.x, d.y, d.z, 0.0]).collect();
    let out = run(&gpu, "cs_oct_encode", &inputs);
    let snorm = |v: f32| (v.clamp(-1.0, 1.0) * 32767.0).round() as i16;
    let mut worst_lsb = 0;
    let mut worst_dir: f32 = 0.0;
    for (d, o) in dirs.iter().zip(&out) {
        let gpu = [snorm(o[0]), snorm(o[1])];
        let cpu = oct_encode(*d);
        worst_dir = worst_dir
            .max(oct_decode(gpu).cross(*d).length())
            .max(oct_decode(gpu).cross(oct_decode(cpu)).length());
        // On the lower hemisphere's fold lines (x or y zero: the signs of −0 and +0) the
        // square's mirrored edges are the same points: either packing may take either
        // edge, and both decode to the direction (checked above).
        if d.z < 0.0 && (d.x == 0.0 || d.y == 0.0) {
            continue;
        }
        let lsb = (0..2)
            .map(|k| (i32::from(gpu[k]) - i32::from(cpu[k])).abs())
            .max()
            .unwrap_or(0);
        worst_lsb = worst_lsb.max(lsb);
    }
    assert!(
        worst_lsb <= 1,
        "the encodings differ by {worst_lsb} snorm16 steps"
    );
    assert!(worst_dir < 1e-4, "a round trip is off by {worst_dir} rad");
}

#[test]
fn the_gray_fraction_is_the_engines() {
    let Some(gpu) = gpu_or_skip("twins: gray fraction") else {
        return;
    };
    let mut cases = Vec::new();
    for ramp in [GrayingRamp::Linear, GrayingRamp::Smoothstep] {
        for i in 0..=40 {
            for j in 0..=40 {
                let (t, onset) = (i as f32 / 40.0, j as f32 / 40.0 * 1.05);
                cases.push((t, onset, ramp));
            }
        }
    }
    let inputs: Vec<[f32; 4]> = cases
        .iter()
        .map(|&(t, onset, ramp)| {
            let smooth = if ramp == GrayingRamp::Smoothstep {
                1.0
            } else {
                0.0
            };
            [t, onset, smooth, 0.0]
        })
        .collect();
    let out = run(&gpu, "cs_gray", &inputs);
    for (&(t, onset, ramp), o) in cases.iter().zip(&out) {
        let cpu = gray_fraction(t, onset, ramp);
        assert!(
            (o[0] - cpu).abs() < 1e-6,
            "t {t}, onset {onset}, {ramp:?}: GPU {} CPU {cpu}",
            o[0]
        );
    }
}

#[test]
fn how_whole_a_hair_is_is_the_engines() {
    let Some(gpu) = gpu_or_skip("twins: hair whole") else {
        return;
    };
    let mut cases = Vec::new();
    for i in 0..=40 {
        for j in 0..=40 {
            cases.push((i as f32 / 40.0, j as f32 / 40.0));
        }
    }
    let inputs: Vec<[f32; 4]> = cases.iter().map(|&(a, t)| [a, t, 0.0, 0.0]).collect();
    let out = run(&gpu, "cs_whole", &inputs);
    for (&(a, t), o) in cases.iter().zip(&out) {
        let cpu = hair_whole(a, t);
        assert!(
            (o[0] - cpu).abs() < 1e-5,
            "a_k {a}, t {t}: GPU {} CPU {cpu}",
            o[0]
        );
    }
}

#[test]
fn the_cavity_is_the_glb_occlusions() {
    let Some(gpu) = gpu_or_skip("twins: cavity") else {
        return;
    };
    let mut cases = Vec::new();
    for i in 0..=50 {
        for disp in [0.0, 0.001, 0.0035, 0.005, 0.02, -0.01] {
            cases.push((i as f32 / 50.0 * 1.2 - 0.1, disp));
        }
    }
    let inputs: Vec<[f32; 4]> = cases.iter().map(|&(l, d)| [l, d, 0.0, 0.0]).collect();
    let out = run(&gpu, "cs_cavity", &inputs);
    for (&(local, disp), o) in cases.iter().zip(&out) {
        let cpu = 1.0 - compose::cavity(local, disp);
        assert!(
            (o[0] - cpu).abs() < 1e-6,
            "local {local}, disp {disp}: GPU loss {} CPU {cpu}",
            o[0]
        );
    }
}

/// The value of the `f32` constant `name` of a naga module.
fn constant(module: &naga::Module, name: &str) -> f32 {
    let (_, c) = module
        .constants
        .iter()
        .find(|(_, c)| c.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("common.wgsl has no constant {name}"));
    match module.global_expressions[c.init] {
        naga::Expression::Literal(naga::Literal::F32(v)) => v,
        ref e => panic!("{name} is not an f32 literal: {e:?}"),
    }
}

#[test]
fn the_cavity_constants_are_the_engines() {
    let module = naga::front::wgsl::parse_str(shaders::COMMON_WGSL).unwrap();
    for (name, cpu) in [
        ("CAVITY", compose::CAVITY),
        ("CAVITY_MAX", compose::CAVITY_MAX),
        ("CAVITY_REFERENCE_DISP", compose::CAVITY_REFERENCE_DISP),
        ("CAVITY_RING", compose::CAVITY_RING),
        ("CREASE_ROUGHNESS", compose::CREASE_ROUGHNESS),
        ("COIL_TURNS", strand::COIL_TURNS),
        ("COIL_RADIUS", strand::COIL_RADIUS),
        (
            "WHITE_HAIR_COVER",
            agesim_core::layers::hair::WHITE_SCALP_HAIR_COVER,
        ),
    ] {
        assert_eq!(constant(&module, name), cpu, "{name}");
    }
}

/// The GLB's hair is the view's: a strand's point and tangent along its curve, straight
/// and coiled, as the hair pass places them.
#[test]
fn the_strand_is_the_hair_passes() {
    let Some(gpu) = gpu_or_skip("twins: strand") else {
        return;
    };
    let mut cases = Vec::new();
    for (k, dir) in directions().into_iter().enumerate().step_by(7) {
        let root = Vec3::new(0.03 * (k as f32 * 0.7).sin(), 0.1, 0.02 * (k as f32).cos());
        for (curl, droop, s) in [
            (0.0, 0.8, 0.5),
            (0.0, 0.3, 1.0),
            (1.0, 0.8, 0.7),
            (0.5, 1.0, 0.25),
        ] {
            let random = (k as f32 * 0.618_034).fract();
            cases.push((root, dir, random, curl, droop, s));
        }
    }
    let (length, unit) = (0.06, 0.06);
    let inputs: Vec<[f32; 4]> = cases
        .iter()
        .flat_map(|&(root, dir, random, curl, droop, s)| {
            [
                [root.x, root.y, root.z, length],
                [dir.x, dir.y, dir.z, random],
                [curl, droop, unit, s],
            ]
        })
        .collect();
    let out = run(&gpu, "cs_strand", &inputs);
    let n = cases.len();
    for (i, &(root, dir, random, curl, droop, s)) in cases.iter().enumerate() {
        let len = strand::strand_length(length, 0.8, random, curl, 0.6);
        let c = strand::hair_curve(root, dir, len, random, curl, droop, unit);
        let (mut p, mut t) = (strand::curve_point(&c, s), strand::curve_tangent(&c, s));
        if curl > 0.0 {
            (p, t) = strand::coiled(p, t, len, s, random, curl);
        }
        let gpu_p = Vec3::from_slice(&out[i][..3]);
        let gpu_t = Vec3::from_slice(&out[n + i][..3]);
        assert!((out[n + i][3] - len).abs() < 1e-6, "case {i}: length");
        assert!(
            gpu_p.distance(p) < 2e-5 * length,
            "case {i}: GPU {gpu_p} CPU {p}"
        );
        assert!(gpu_t.distance(t) < 2e-4, "case {i}: GPU {gpu_t} CPU {t}");
    }
}
