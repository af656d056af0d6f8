//! Shows a texture in a render pass someone else owns (the editor's egui pass): one
//! triangle over the pass's current viewport, sampling the texture as it is, without
//! blending. On a CPU rasteriser this costs a fraction of a general textured-quad shader
//! per pixel (egui's multiplies a vertex colour, dithers and blends).

use crate::shaders;

/// A blit pipeline for one target format, and its sampler.
pub struct Blit {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
}

impl Blit {
    /// A pipeline drawing into `target_format` (no depth, one sample). The texture's
    /// values are written as they are; into an sRGB target they are decoded first, so
    /// the hardware's encoding gives them back.
    pub fn new(device: &wgpu::Device, target_format: wgpu::TextureFormat) -> Self {
        Self::build(device, target_format, false)
    }

    /// A pipeline drawing one texture with a second laid over it (`blit.wgsl`'s
    /// `fs_over`: both premultiplied, as egui's pictures are; the result opaque), bound
    /// by [`Blit::bind_over`].
    pub fn new_over(device: &wgpu::Device, target_format: wgpu::TextureFormat) -> Self {
        Self::build(device, target_format, true)
    }

    fn build(device: &wgpu::Device, target_format: wgpu::TextureFormat, over: bool) -> Self {
        let texture = |binding: u32| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        };
        let mut entries = vec![
            texture(0),
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
        ];
        if over {
            entries.push(texture(2));
        }
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("agesim blit bind group layout"),
            entries: &entries,
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("agesim blit.wgsl"),
            source: wgpu::ShaderSource::Wgsl(shaders::BLIT_WGSL.into()),
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("agesim blit pipeline layout"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = fullscreen_pipeline(
            device,
            "agesim blit pipeline",
            &pipeline_layout,
            &module,
            ("vs_main", if over { "fs_over" } else { "fs_main" }),
            target_format,
            &[(
                "DECODE_SRGB",
                if target_format.is_srgb() { 1.0 } else { 0.0 },
            )],
        );
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("agesim blit sampler"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        Self {
            pipeline,
            layout,
            sampler,
        }
    }

    /// The bind group showing `view` (make one per texture, keep it while it lives).
    pub fn bind(&self, device: &wgpu::Device, view: &wgpu::TextureView) -> wgpu::BindGroup {
        self.bind_entries(device, view, None)
    }

    /// The bind group of a [`Blit::new_over`] pipeline: `overlay` over `base`.
    pub fn bind_over(
        &self,
        device: &wgpu::Device,
        base: &wgpu::TextureView,
        overlay: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        self.bind_entries(device, base, Some(overlay))
    }

    fn bind_entries(
        &self,
        device: &wgpu::Device,
        view: &wgpu::TextureView,
        overlay: Option<&wgpu::TextureView>,
    ) -> wgpu::BindGroup {
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(view),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::Sampler(&self.sampler),
            },
        ];
        if let Some(o) = overlay {
            entries.push(wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(o),
            });
        }
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("agesim blit bind group"),
            layout: &self.layout,
            entries: &entries,
        })
    }

    /// Draws the texture of `bind_group` over the pass's viewport.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>, bind_group: &wgpu::BindGroup) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// A pipeline drawing one viewport-covering triangle (`vs` takes only the vertex index,
/// no vertex buffers), without depth, blending or multisampling, into `format`.
pub(crate) fn fullscreen_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::PipelineLayout,
    module: &wgpu::ShaderModule,
    (vs, fs): (&str, &str),
    format: wgpu::TextureFormat,
    fragment_constants: &[(&str, f64)],
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(vs),
            buffers: &[],
            compilation_options: wgpu::PipelineCompilationOptions::default(),
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fs),
            targets: &[Some(wgpu::ColorTargetState {
                format,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: fragment_constants,
                ..Default::default()
            },
        }),
        multiview_mask: None,
        cache: None,
    })
}
