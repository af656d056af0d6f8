//! A headless device for the command line, tests and benchmarks. The editor does not use
//! this: it hands eframe's device to [`crate::Renderer::new`].

use crate::RenderError;

/// An adapter, its device and queue, created without a window.
pub struct Gpu {
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
}

impl Gpu {
    /// Picks the default adapter (on the CI and dev machines lavapipe, the CPU Vulkan
    /// driver; `WGPU_BACKEND`/`WGPU_ADAPTER_NAME` are honoured) with the default limits.
    pub fn new() -> Result<Self, RenderError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter =
            pollster::block_on(
                instance.request_adapter(&wgpu::RequestAdapterOptions {
                    power_preference: wgpu::PowerPreference::from_env()
                        .unwrap_or(wgpu::PowerPreference::HighPerformance),
                    force_fallback_adapter: false,
                    compatible_surface: None,
                    ..Default::default()
                }),
            )
            .map_err(|e| RenderError::NoAdapter(e.to_string()))?;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("agesim headless device"),
            ..Default::default()
        }))
        .map_err(|e| RenderError::Device(e.to_string()))?;
        Ok(Self {
            adapter,
            device,
            queue,
        })
    }

    /// "name (backend, device type)", for the command line and the benchmark table.
    pub fn adapter_description(&self) -> String {
        let info = self.adapter.get_info();
        format!(
            "{} ({:?}, {:?}, driver {})",
            info.name, info.backend, info.device_type, info.driver_info
        )
    }
}

/// The one skip rule of the GPU and window tests: in CI (`CI=true`) a missing adapter,
/// driver or display is a failure; elsewhere the test prints why and passes.
pub mod ci {
    /// Whether this run is CI's (`CI=true`), where nothing may be skipped.
    pub fn required() -> bool {
        std::env::var("CI").is_ok_and(|v| v == "true")
    }

    /// Panics with `reason` in CI; elsewhere prints that `test` is skipped and why.
    pub fn skip_or_fail(test: &str, reason: &str) {
        if required() {
            panic!("{test}: {reason} (required in CI, CI=true)");
        }
        eprintln!("{test}: skipped, {reason}");
    }

    /// The headless GPU, or `None` after [`skip_or_fail`].
    pub fn gpu_or_skip(test: &str) -> Option<super::Gpu> {
        match super::Gpu::new() {
            Ok(gpu) => Some(gpu),
            Err(e) => {
                skip_or_fail(
                    test,
                    &format!("no GPU adapter: {e} (install mesa-vulkan-drivers)"),
                );
                None
            }
        }
    }
}
