//! A user's program with only the emitted WGSL text and the interface, compiled with the host
//! folded in (`patina compile --fold-host`), and no Patina code at draw time: its own camera
//! (glam's left-handed look-at and perspective), its own uniform packing from the interface's
//! layout, its own bind groups and pipeline. It draws plastic, planet and bricks as `patina
//! render` draws their scenes, within the gallery's thresholds.
//!
//! The test harness reads each scene (for the values a user would know: camera, parameters,
//! lights, the mesh's vertices) and renders the reference with the runtime; everything between
//! the compiled artifacts and the pixels is the "user" code below.

use std::borrow::Cow;

use glam::{Mat4, Vec3};
use patina::interface::{AttributeSource, MeshAttribute, ScalarKind, UniformSource};
use patina::runtime::image::{Image, Thresholds, compare};
use patina::runtime::mesh::Mesh;
use patina::runtime::scene::{ParamValue, Scene, ShaderRef};
use patina::runtime::{gpu, render};
use patina::{Compiler, Interface, Light};
use wgpu::util::DeviceExt;

/// The artifacts a user keeps: what `patina compile --fold-host` writes.
fn compile(scene: &Scene) -> (String, String) {
    let object = &scene.objects[0];
    let mut compiler = Compiler::new().fold_host(true);
    for l in &scene.lights {
        compiler =
            compiler.light(Light::file(&l.shader.path).named(l.shader.name.as_deref().unwrap_or_default()));
    }
    let compiled = compiler.compile_file(&object.surface.path).expect("compiles");
    assert!(!compiled.interface.needs_host, "a folded program needs no host part");
    (compiled.wgsl, serde_json::to_string(&compiled.interface).expect("json"))
}

// ---- The user's code: from here on, only the WGSL, the JSON, glam and wgpu. ----

/// A value the user gives, in their world space, typed by the interface's type name.
fn in_camera(ty: &str, v: &[f64], view: Mat4) -> Vec<f64> {
    let p = || Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32);
    let out = match ty {
        "point" => view.transform_point3(p()),
        "vector" => view.transform_vector3(p()),
        "normal" => view.inverse().transpose().transform_vector3(p()),
        _ => return v.to_vec(),
    };
    out.to_array().iter().map(|x| f64::from(*x)).collect()
}

/// The user's uniform block: every member from its source, written at its offset as the
/// interface's layout says (matrices as `to_cols_array`).
fn pack(interface: &Interface, values: &UserValues) -> Vec<u8> {
    let mut block = vec![0u8; interface.uniform_size as usize];
    let cols = |m: Mat4| m.to_cols_array().iter().map(|x| f64::from(*x)).collect::<Vec<_>>();
    let model_view = values.view * values.model;
    for field in &interface.uniforms {
        let v: Vec<f64> = match &field.source {
            UniformSource::Geometry { matrix } => match format!("{matrix:?}").as_str() {
                "ObjectToCamera" => cols(model_view),
                "NormalToCamera" => cols(model_view.inverse().transpose()),
                "CameraToClip" => cols(values.projection),
                other => panic!("geometry {other}"),
            },
            // The matrix from camera space to object space, and back.
            UniformSource::Space { name, inverse, light: None } if name == "object" => {
                cols(if *inverse { model_view } else { model_view.inverse() })
            }
            UniformSource::Global { name } if name == "Cs" => {
                values.color.iter().map(|x| f64::from(*x)).collect()
            }
            UniformSource::Global { name } if name == "Os" => {
                values.opacity.iter().map(|x| f64::from(*x)).collect()
            }
            UniformSource::Param { name } => {
                let p = interface.param(name).expect("a parameter the interface lists");
                let given = values.surface.iter().find(|(n, _)| n == name).map(|(_, v)| v.clone());
                in_camera(&p.ty, &given.or(p.default.clone()).expect("a value or a default"), values.view)
            }
            UniformSource::LightParam { light, name } => {
                let p = interface.lights[*light].params.iter().find(|p| p.name == *name).expect("listed");
                let given = values.lights[*light].iter().find(|(n, _)| n == name).map(|(_, v)| v.clone());
                in_camera(&p.ty, &given.or(p.default.clone()).expect("a value or a default"), values.view)
            }
            // A noise's permutation or gradients: the same values every draw.
            UniformSource::Table { values } => values.clone(),
            other => panic!("this user program does not fill {other:?}"),
        };
        let l = &field.layout;
        for e in 0..l.elements {
            for c in 0..l.components {
                let Some(x) = v.get((e * l.components + c) as usize) else { continue };
                let within =
                    if l.column_stride > 0 { (c / 3) * l.column_stride + (c % 3) * 4 } else { c * 4 };
                let at = (field.offset + e * l.element_stride + within) as usize;
                let word = match l.scalar {
                    ScalarKind::F32 => (*x as f32).to_le_bytes(),
                    _ => (*x as i32).to_le_bytes(),
                };
                block[at..at + 4].copy_from_slice(&word);
            }
        }
    }
    block
}

/// What the user knows of their scene.
struct UserValues {
    view: Mat4,
    projection: Mat4,
    model: Mat4,
    color: [f32; 3],
    opacity: [f32; 3],
    surface: Vec<(String, Vec<f64>)>,
    lights: Vec<Vec<(String, Vec<f64>)>>,
    /// The image's size and the (premultiplied) colour it is cleared to.
    size: (u32, u32),
    clear: [f64; 4],
}

/// Draws `mesh` with the WGSL text and the interface on `device` into an RGBA32F image.
fn draw(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    wgsl: &str,
    json: &str,
    values: &UserValues,
    mesh: &Mesh,
) -> Image {
    let (size, clear) = (values.size, values.clear);
    let interface: Interface = serde_json::from_str(json).expect("the interface JSON");
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(wgsl)),
    });
    let init = |contents: &[u8], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: None, contents, usage })
    };
    let uniforms = init(&pack(&interface, values), wgpu::BufferUsages::UNIFORM);
    let entry = wgpu::BindGroupLayoutEntry {
        binding: 0,
        visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    let layout =
        device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: None, entries: &[entry] });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &layout,
        entries: &[wgpu::BindGroupEntry { binding: 0, resource: uniforms.as_entire_binding() }],
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: None,
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let mut buffers = Vec::new();
    let mut attributes = Vec::new();
    for a in &interface.attributes {
        let data: Vec<f32> = match &a.source {
            AttributeSource::Mesh { what: MeshAttribute::Position } => mesh.positions.as_flattened().to_vec(),
            AttributeSource::Mesh { what: MeshAttribute::Normal } => mesh.normals.as_flattened().to_vec(),
            AttributeSource::Mesh { what: MeshAttribute::Uv } => mesh.uvs.as_flattened().to_vec(),
            AttributeSource::Mesh { what: MeshAttribute::DpDu } => mesh.dpdu.as_flattened().to_vec(),
            AttributeSource::Mesh { what: MeshAttribute::DpDv } => mesh.dpdv.as_flattened().to_vec(),
            other => panic!("this user program has no {other:?}"),
        };
        buffers.push(init(bytemuck::cast_slice(&data), wgpu::BufferUsages::VERTEX));
        let format =
            [wgpu::VertexFormat::Float32, wgpu::VertexFormat::Float32x2, wgpu::VertexFormat::Float32x3]
                [a.components as usize - 1];
        attributes.push(wgpu::VertexAttribute { format, offset: 0, shader_location: a.location });
    }
    let vertex_layouts: Vec<_> = attributes
        .iter()
        .map(|a| {
            Some(wgpu::VertexBufferLayout {
                array_stride: a.format.size(),
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: std::slice::from_ref(a),
            })
        })
        .collect();
    let format = wgpu::TextureFormat::Rgba32Float;
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: None,
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some(&interface.vertex_entry),
            compilation_options: Default::default(),
            buffers: &vertex_layouts,
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: wgpu::TextureFormat::Depth32Float,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some(&interface.fragment_entry),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    let extent = wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 };
    let texture = |format, usage| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: None,
            size: extent,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    };
    let colour = texture(format, wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC);
    let depth = texture(wgpu::TextureFormat::Depth32Float, wgpu::TextureUsages::RENDER_ATTACHMENT);
    let (colour_view, depth_view) =
        (colour.create_view(&Default::default()), depth.create_view(&Default::default()));
    let indices = init(bytemuck::cast_slice(&mesh.indices), wgpu::BufferUsages::INDEX);
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let [r, g, b, a] = clear;
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &colour_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            ..Default::default()
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        for (slot, b) in buffers.iter().enumerate() {
            pass.set_vertex_buffer(slot as u32, b.slice(..));
        }
        pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..mesh.indices.len() as u32, 0, 0..1);
    }
    let row = (size.0 * 16).next_multiple_of(256);
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: u64::from(row * size.1),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let layout = wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: None };
    encoder.copy_texture_to_buffer(
        colour.as_image_copy(),
        wgpu::TexelCopyBufferInfo { buffer: &readback, layout },
        extent,
    );
    queue.submit([encoder.finish()]);
    readback.map_async(wgpu::MapMode::Read, .., |r| r.expect("map"));
    device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    let bytes = readback.get_mapped_range(..).expect("mapped").to_vec();
    let floats: &[f32] = bytemuck::cast_slice(&bytes);
    let pixels = (0..size.1)
        .flat_map(|y| (0..size.0).map(move |x| ((y * row / 4 + x * 4) as usize, x)))
        .map(|(at, _)| [floats[at], floats[at + 1], floats[at + 2], floats[at + 3]])
        .collect();
    Image { width: size.0, height: size.1, pixels }
}

// ---- The harness. ----

fn numbers(shader: &ShaderRef) -> Vec<(String, Vec<f64>)> {
    shader
        .params
        .iter()
        .filter_map(|(name, v)| {
            let v = match v {
                ParamValue::Number(x) => vec![*x],
                ParamValue::Numbers(v) => v.clone(),
                ParamValue::Bool(b) => vec![f64::from(u8::from(*b))],
                ParamValue::String(_) => return None,
            };
            Some((name.clone(), v))
        })
        .collect()
}

fn standalone_matches_the_renderer(name: &str) {
    let Some(gpu) = gpu::for_tests() else { return };
    let path = format!("{}/examples/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let scene = Scene::load(&path).expect("scene");
    let reference =
        render::render(&render::prepare(&scene).expect("prepare"), render::Backend::Gpu, Some(gpu))
            .expect("render");

    let (wgsl, json) = compile(&scene);
    let object = &scene.objects[0];
    let camera = scene.camera();
    let (width, height) = (scene.output.width, scene.output.height);
    let [r, g, b, a] = scene.output.background.map(f64::from);
    let values = UserValues {
        view: Mat4::look_at_lh(camera.from, camera.to, camera.up),
        projection: Mat4::perspective_lh(
            camera.fov_y_degrees.to_radians(),
            width as f32 / height as f32,
            camera.near,
            camera.far,
        ),
        model: scene.object_transform(0),
        color: object.color,
        opacity: object.opacity,
        surface: numbers(&object.surface),
        lights: scene.lights.iter().map(|l| numbers(&l.shader)).collect(),
        size: (width, height),
        clear: [r * a, g * a, b * a, a],
    };
    let mesh = object.build_mesh().expect("mesh");
    let drawn = draw(gpu.device(), gpu.queue(), &wgsl, &json, &values, &mesh);
    let c = compare(&drawn, &reference, &Thresholds::default()).expect("same size");
    assert!(c.passes(&Thresholds::default()), "{name}: {c:?}");
    // The picture is not empty: the object covers a good part of the image.
    let lit =
        drawn.pixels.iter().filter(|p| (p[0] - r as f32).abs() + (p[1] - g as f32).abs() > 0.05).count();
    assert!(lit > drawn.pixels.len() / 10, "{name}: {lit} lit pixels");
}

#[test]
fn plastic_drawn_without_patina_matches_patina_render() {
    standalone_matches_the_renderer("plastic");
}

#[test]
fn planet_drawn_without_patina_matches_patina_render() {
    standalone_matches_the_renderer("planet");
}

#[test]
fn bricks_drawn_without_patina_matches_patina_render() {
    standalone_matches_the_renderer("bricks");
}
