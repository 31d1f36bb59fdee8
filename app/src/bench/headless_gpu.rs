//! egui drawn with wgpu into an offscreen texture, without a window: what
//! eframe does every frame (texture uploads, buffers, paint callbacks, the
//! render pass, the wait for the GPU), for benchmarks of whole frames.

use eframe::egui_wgpu::{
    RenderState, RendererOptions, ScreenDescriptor, WgpuConfiguration, WgpuSetup,
    WgpuSetupCreateNew,
};
use eframe::wgpu;

/// A wgpu device with egui's renderer and a target the size of the screen.
pub struct HeadlessGpu {
    /// The device, queue and egui renderer.
    pub render_state: RenderState,
    target: wgpu::TextureView,
    size: [u32; 2],
}

impl HeadlessGpu {
    /// Opens the first adapter wgpu offers (on a machine without a GPU:
    /// Mesa's lavapipe) with a `size`-pixel target.
    pub fn new(size: [u32; 2]) -> anyhow::Result<Self> {
        let setup = WgpuSetup::CreateNew(WgpuSetupCreateNew::without_display_handle());
        let instance = pollster::block_on(setup.new_instance());
        let render_state = pollster::block_on(RenderState::create(
            &WgpuConfiguration {
                wgpu_setup: setup,
                ..Default::default()
            },
            &instance,
            None,
            RendererOptions::default(),
        ))?;
        let target = render_state
            .device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some("headless frame"),
                size: wgpu::Extent3d {
                    width: size[0],
                    height: size[1],
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: render_state.target_format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
                view_formats: &[],
            })
            .create_view(&wgpu::TextureViewDescriptor::default());
        Ok(Self {
            render_state,
            target,
            size,
        })
    }

    /// The adapter's name and backend, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) on Vulkan".
    pub fn adapter(&self) -> String {
        let info = self.render_state.adapter.get_info();
        format!("{} on {:?}", info.name, info.backend)
    }

    /// Draws one egui frame and waits until the GPU has finished it.
    pub fn draw(&self, ctx: &egui::Context, mut output: egui::FullOutput) -> anyhow::Result<()> {
        let rs = &self.render_state;
        let mut renderer = rs.renderer.write();
        for (id, deltas) in &output.textures_delta.set {
            for delta in deltas {
                renderer.update_texture(&rs.device, &rs.queue, *id, delta);
            }
        }
        let screen = ScreenDescriptor {
            size_in_pixels: self.size,
            pixels_per_point: output.pixels_per_point,
        };
        let primitives = ctx.tessellate(output.shapes, output.pixels_per_point);
        let mut encoder = rs
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        let user_buffers =
            renderer.update_buffers(&rs.device, &rs.queue, &mut encoder, &primitives, &screen);
        {
            let mut pass = encoder
                .begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("headless frame"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: &self.target,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    ..Default::default()
                })
                .forget_lifetime();
            renderer.render(&mut pass, &primitives, &screen);
        }
        rs.queue.submit(
            user_buffers
                .into_iter()
                .chain(std::iter::once(encoder.finish())),
        );
        rs.device.poll(wgpu::PollType::wait_indefinitely())?;
        for id in &output.textures_delta.free {
            renderer.free_texture(id);
        }
        output.textures_delta.clear();
        Ok(())
    }
}
