//! The debug view's wgpu side: pipelines created once per device, an
//! offscreen multisampled target with depth, and the egui paint callback
//! that renders the drawing into it and blits the result into egui's pass.

use eframe::egui_wgpu::{self, CallbackResources, CallbackTrait, RenderState, ScreenDescriptor};
use eframe::wgpu;
use glam::{Mat4, Vec3};
use std::sync::Arc;
use wgpu::util::DeviceExt;

/// Samples per pixel of the offscreen target (lines and silhouettes stay smooth).
const SAMPLES: u32 = 4;
/// The offscreen colour format; the shaders write sRGB-encoded values into it,
/// as egui does into its own non-sRGB target.
const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// A shaded-mesh vertex as the GPU reads it: position, unit normal and
/// linear RGB base colour.
pub type GpuVertex = [f32; 9];

/// A line segment as the GPU reads it: start a, end b (world), premultiplied
/// sRGB RGBA in [0, 1] (egui's `Color32`), width in points.
pub type GpuSegment = [f32; 11];

/// Floats as the bytes a buffer holds.
fn bytes<const N: usize>(values: &[[f32; N]]) -> Vec<u8> {
    values
        .iter()
        .flatten()
        .flat_map(|v| v.to_ne_bytes())
        .collect()
}

/// Everything the GPU draws for one state of the scene; `version` changes
/// whenever the contents do, so buffers are uploaded only then.
#[derive(Debug, Default)]
pub struct GpuScene {
    /// Identifies these contents.
    pub version: u64,
    /// Shaded triangles, three vertices each.
    pub triangles: Vec<GpuVertex>,
    /// Wide line segments.
    pub segments: Vec<GpuSegment>,
}

/// The shader's `Uniforms`: view_proj (16), viewport (2), pixels per point,
/// padding, light (4).
type Uniforms = [f32; 24];

fn uniforms(view_proj: Mat4, size: [u32; 2], pixels_per_point: f32, light: Vec3) -> Uniforms {
    let mut u = [0.0; 24];
    u[..16].copy_from_slice(&view_proj.to_cols_array());
    u[16] = size[0] as f32;
    u[17] = size[1] as f32;
    u[18] = pixels_per_point;
    u[20..23].copy_from_slice(&light.to_array());
    u
}

/// What one frame of the view needs: the drawing, the observer and the size.
pub struct DebugCallback {
    /// The drawing.
    pub scene: Arc<GpuScene>,
    /// World to clip space.
    pub view_proj: Mat4,
    /// Unit vector toward the headlight.
    pub light: Vec3,
    /// The background, premultiplied sRGB.
    pub background: egui::Color32,
}

/// The size of the offscreen target and what it last showed.
struct Target {
    size: [u32; 2],
    color: wgpu::TextureView,
    resolved: wgpu::TextureView,
    depth: wgpu::TextureView,
    blit: wgpu::BindGroup,
    /// (scene version, uniforms, background) last rendered: unchanged → no re-render.
    shown: Option<(u64, Uniforms, [u8; 4])>,
}

/// The pipelines and buffers, kept in egui-wgpu's callback resources.
pub struct DebugRenderer {
    mesh_pipeline: wgpu::RenderPipeline,
    line_pipeline: wgpu::RenderPipeline,
    blit_pipeline: wgpu::RenderPipeline,
    blit_layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    uniforms: wgpu::Buffer,
    uniform_group: wgpu::BindGroup,
    triangles: Option<(wgpu::Buffer, u32)>,
    segments: Option<(wgpu::Buffer, u32)>,
    uploaded: Option<u64>,
    target: Option<Target>,
}

impl DebugRenderer {
    /// Creates the pipelines once for this device, unless they exist already.
    pub fn install(render_state: &RenderState) {
        if render_state
            .renderer
            .read()
            .callback_resources
            .contains::<DebugRenderer>()
        {
            return;
        }
        let mut renderer = render_state.renderer.write();
        if renderer.callback_resources.contains::<DebugRenderer>() {
            return;
        }
        let debug = DebugRenderer::new(&render_state.device, render_state.target_format);
        renderer.callback_resources.insert(debug);
    }

    fn new(device: &wgpu::Device, target_format: wgpu::TextureFormat) -> Self {
        let shader = device.create_shader_module(wgpu::include_wgsl!("shader.wgsl"));
        let uniform_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("debug view uniforms"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let uniforms = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("debug view uniforms"),
            size: std::mem::size_of::<Uniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let uniform_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("debug view uniforms"),
            layout: &uniform_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniforms.as_entire_binding(),
            }],
        });
        let scene_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("debug view scene"),
            bind_group_layouts: &[Some(&uniform_layout)],
            immediate_size: 0,
        });
        let depth = |write: bool| wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(write),
            depth_compare: Some(wgpu::CompareFunction::LessEqual),
            stencil: wgpu::StencilState::default(),
            bias: wgpu::DepthBiasState::default(),
        };
        let multisample = wgpu::MultisampleState {
            count: SAMPLES,
            ..Default::default()
        };
        let mesh_attributes =
            wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x3];
        let mesh_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("debug view meshes"),
            layout: Some(&scene_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("mesh_vs"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: std::mem::size_of::<GpuVertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &mesh_attributes,
                })],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(depth(true)),
            multisample,
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some("mesh_fs"),
                compilation_options: Default::default(),
                targets: &[Some(COLOR_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let line_attributes =
            wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x4, 3 => Float32];
        let line_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("debug view lines"),
            layout: Some(&scene_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("line_vs"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: std::mem::size_of::<GpuSegment>() as u64,
                    step_mode: wgpu::VertexStepMode::Instance,
                    attributes: &line_attributes,
                })],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(depth(false)),
            multisample,
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some("line_fs"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: COLOR_FORMAT,
                    blend: Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let blit_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("debug view blit"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let blit_pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("debug view blit"),
            bind_group_layouts: &[Some(&blit_layout)],
            immediate_size: 0,
        });
        let blit_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("debug view blit"),
            layout: Some(&blit_pipeline_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("blit_vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some("blit_fs"),
                compilation_options: Default::default(),
                targets: &[Some(target_format.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("debug view blit"),
            ..Default::default()
        });
        Self {
            mesh_pipeline,
            line_pipeline,
            blit_pipeline,
            blit_layout,
            sampler,
            uniforms,
            uniform_group,
            triangles: None,
            segments: None,
            uploaded: None,
            target: None,
        }
    }

    /// Uploads the drawing when its version changed.
    fn upload(&mut self, device: &wgpu::Device, scene: &GpuScene) {
        if self.uploaded == Some(scene.version) {
            return;
        }
        let buffer = |label: &str, bytes: &[u8]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytes,
                usage: wgpu::BufferUsages::VERTEX,
            })
        };
        self.triangles = (!scene.triangles.is_empty()).then(|| {
            (
                buffer("debug view triangles", &bytes(&scene.triangles)),
                scene.triangles.len() as u32,
            )
        });
        self.segments = (!scene.segments.is_empty()).then(|| {
            (
                buffer("debug view segments", &bytes(&scene.segments)),
                scene.segments.len() as u32,
            )
        });
        self.uploaded = Some(scene.version);
    }

    /// (Re)creates the offscreen target for `size` physical pixels.
    fn target(&mut self, device: &wgpu::Device, size: [u32; 2]) -> &mut Target {
        if self.target.as_ref().is_none_or(|t| t.size != size) {
            let texture = |label: &str, format, samples, usage| {
                device
                    .create_texture(&wgpu::TextureDescriptor {
                        label: Some(label),
                        size: wgpu::Extent3d {
                            width: size[0],
                            height: size[1],
                            depth_or_array_layers: 1,
                        },
                        mip_level_count: 1,
                        sample_count: samples,
                        dimension: wgpu::TextureDimension::D2,
                        format,
                        usage,
                        view_formats: &[],
                    })
                    .create_view(&wgpu::TextureViewDescriptor::default())
            };
            let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT;
            let resolved = texture(
                "debug view picture",
                COLOR_FORMAT,
                1,
                attachment | wgpu::TextureUsages::TEXTURE_BINDING,
            );
            let blit = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("debug view blit"),
                layout: &self.blit_layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(&resolved),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: wgpu::BindingResource::Sampler(&self.sampler),
                    },
                ],
            });
            self.target = Some(Target {
                size,
                color: texture("debug view colour", COLOR_FORMAT, SAMPLES, attachment),
                depth: texture("debug view depth", DEPTH_FORMAT, SAMPLES, attachment),
                resolved,
                blit,
                shown: None,
            });
        }
        self.target.as_mut().expect("the target was just created")
    }
}

/// The physical pixel size of the callback's rectangle.
fn size_in_pixels(rect: egui::Rect, pixels_per_point: f32) -> [u32; 2] {
    [
        ((rect.width() * pixels_per_point).round() as u32).max(1),
        ((rect.height() * pixels_per_point).round() as u32).max(1),
    ]
}

/// The callback for one frame of the view covering `rect`.
pub fn paint_callback(rect: egui::Rect, callback: DebugCallback) -> egui::PaintCallback {
    egui_wgpu::Callback::new_paint_callback(rect, CallbackWithRect { rect, callback })
}

struct CallbackWithRect {
    rect: egui::Rect,
    callback: DebugCallback,
}

impl CallbackTrait for CallbackWithRect {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        screen: &ScreenDescriptor,
        encoder: &mut wgpu::CommandEncoder,
        resources: &mut CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        let Some(debug) = resources.get_mut::<DebugRenderer>() else {
            return Vec::new();
        };
        let c = &self.callback;
        let size = size_in_pixels(self.rect, screen.pixels_per_point);
        let uniforms = uniforms(c.view_proj, size, screen.pixels_per_point, c.light);
        debug.upload(device, &c.scene);
        let key = (c.scene.version, uniforms, c.background.to_array());
        if debug.target(device, size).shown == Some(key) {
            return Vec::new();
        }
        queue.write_buffer(&debug.uniforms, 0, &bytes(&[uniforms]));
        let target = debug.target.as_ref().expect("created above");
        let [r, g, b, a] = c.background.to_array().map(|v| f64::from(v) / 255.0);
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("debug view"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target.color,
                    depth_slice: None,
                    resolve_target: Some(&target.resolved),
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a }),
                        store: wgpu::StoreOp::Discard,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &target.depth,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &debug.uniform_group, &[]);
            if let Some((buffer, count)) = &debug.triangles {
                pass.set_pipeline(&debug.mesh_pipeline);
                pass.set_vertex_buffer(0, buffer.slice(..));
                pass.draw(0..*count, 0..1);
            }
            if let Some((buffer, count)) = &debug.segments {
                pass.set_pipeline(&debug.line_pipeline);
                pass.set_vertex_buffer(0, buffer.slice(..));
                pass.draw(0..6, 0..*count);
            }
        }
        if let Some(target) = debug.target.as_mut() {
            target.shown = Some(key);
        }
        Vec::new()
    }

    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        resources: &CallbackResources,
    ) {
        let Some(debug) = resources.get::<DebugRenderer>() else {
            return;
        };
        let Some(target) = &debug.target else {
            return;
        };
        pass.set_pipeline(&debug.blit_pipeline);
        pass.set_bind_group(0, &target.blit, &[]);
        pass.draw(0..3, 0..1);
    }
}
