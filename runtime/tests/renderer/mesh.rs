//! The built-in shapes, OBJ loading, transformation and validation, through the public API.

use glam::{Mat4, Vec3};
use patina_runtime::mesh::{MAX_DETAIL, Mesh, MeshError};
use std::f32::consts::PI;
use std::path::PathBuf;

fn v(a: [f32; 3]) -> Vec3 {
    Vec3::from(a)
}

/// Every triangle's `(b − a) × (c − a)` agrees with its vertices' normals, and every normal is a
/// unit vector.
fn assert_wound_outwards(mesh: &Mesh) {
    mesh.validate().unwrap();
    for n in &mesh.normals {
        assert!((v(*n).length() - 1.0).abs() < 1e-4, "normal {n:?} is not unit");
    }
    for t in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| v(mesh.positions[t[k] as usize]));
        let face = (b - a).cross(c - a);
        if face.length() < 1e-9 {
            continue;
        }
        let normal: Vec3 = t.iter().map(|&i| v(mesh.normals[i as usize])).sum();
        assert!(face.dot(normal) > 0.0, "triangle {t:?} faces against its normals");
    }
}

/// `dpdu × dpdv` points along the normal wherever it is not zero.
fn assert_derivatives_along_normals(mesh: &Mesh) {
    for i in 0..mesh.vertex_count() {
        let cross = v(mesh.dpdu[i]).cross(v(mesh.dpdv[i]));
        if cross.length() > 1e-6 {
            assert!(cross.normalize().dot(v(mesh.normals[i])) > 0.99, "vertex {i}");
        }
    }
}

/// The enclosed volume by the divergence theorem; positive when the winding is outwards.
fn volume(mesh: &Mesh) -> f32 {
    let p = |i: u32| v(mesh.positions[i as usize]);
    mesh.indices.chunks_exact(3).map(|t| p(t[0]).dot(p(t[1]).cross(p(t[2]))) / 6.0).sum()
}

#[test]
fn sphere_is_renderman_parameterized() {
    let mesh = Mesh::sphere(2.0, 32, 16);
    assert_eq!(mesh.vertex_count(), 33 * 17);
    assert_eq!(mesh.triangle_count(), 2 * 32 * 16 - 2 * 32, "the pole triangles are dropped");
    assert_wound_outwards(&mesh);
    assert_derivatives_along_normals(&mesh);
    for i in 0..mesh.vertex_count() {
        let (p, [u, vv]) = (v(mesh.positions[i]), mesh.uvs[i]);
        assert!((p.length() - 2.0).abs() < 1e-5);
        assert!(v(mesh.normals[i]).abs_diff_eq(p / 2.0, 1e-5));
        assert!((p.z - 2.0 * (PI * (vv - 0.5)).sin()).abs() < 1e-5, "v runs from the -z pole to the +z pole");
        if vv > 0.0 && vv < 1.0 {
            // The analytic dP/du, against the longitude.
            let expected = 2.0 * PI * Vec3::new(-p.y, p.x, 0.0);
            assert!(v(mesh.dpdu[i]).abs_diff_eq(expected, 1e-4), "u = {u}");
        }
    }
    let exact = 4.0 / 3.0 * PI * 8.0;
    assert!((volume(&mesh) - exact).abs() < 0.03 * exact);
}

#[test]
fn torus_is_wound_outwards() {
    let mesh = Mesh::torus(1.0, 0.25, 48, 24);
    assert_wound_outwards(&mesh);
    assert_derivatives_along_normals(&mesh);
    let exact = 2.0 * PI * PI * 1.0 * 0.25 * 0.25;
    assert!((volume(&mesh) - exact).abs() < 0.02 * exact, "{}", volume(&mesh));
    // u = 0, v = 0 is the outer equator on +x.
    assert!(v(mesh.positions[0]).abs_diff_eq(Vec3::new(1.25, 0.0, 0.0), 1e-6));
}

#[test]
fn plane_faces_the_default_camera_with_upright_texture() {
    let mesh = Mesh::plane(2.0, 4);
    assert_wound_outwards(&mesh);
    assert_derivatives_along_normals(&mesh);
    assert!(mesh.normals.iter().all(|n| *n == [0.0, 0.0, -1.0]));
    assert_eq!(mesh.positions[0], [-1.0, 1.0, 0.0], "(u, v) = (0, 0) is the top-left corner");
    assert_eq!(mesh.uvs[0], [0.0, 0.0]);
    assert_eq!(mesh.dpdu[0], [2.0, 0.0, 0.0]);
    assert_eq!(mesh.dpdv[0], [0.0, -2.0, 0.0]);
    assert_eq!(mesh.triangle_count(), 32);
}

#[test]
fn cube_has_flat_faces_wound_outwards() {
    let mesh = Mesh::cube(2.0);
    assert_eq!((mesh.vertex_count(), mesh.triangle_count()), (24, 12));
    assert_wound_outwards(&mesh);
    assert_derivatives_along_normals(&mesh);
    assert!((volume(&mesh) - 8.0).abs() < 1e-5);
    for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
        assert_eq!(v(*p).dot(v(*n)), 1.0, "every vertex lies on its face's plane");
    }
}

#[test]
fn teapot_is_the_newell_teapot() {
    let mesh = Mesh::teapot(6);
    assert_eq!(mesh.vertex_count(), 32 * 7 * 7);
    assert_wound_outwards(&mesh);
    assert_derivatives_along_normals(&mesh);
    let (lo, hi) = mesh.bounds().unwrap();
    assert!(lo.abs_diff_eq(Vec3::new(-3.0, -2.0, 0.0), 0.01), "{lo}");
    assert!(hi.abs_diff_eq(Vec3::new(3.434, 2.0, 3.15), 0.01), "{hi}");
    // The body's widest point, on +x, faces +x.
    let widest = (0..mesh.vertex_count()).find(|&i| mesh.positions[i] == [2.0, 0.0, 0.9]);
    let normal = v(mesh.normals[widest.expect("a patch corner at the widest point")]);
    assert!(normal.abs_diff_eq(Vec3::X, 1e-4), "{normal}");
}

#[test]
fn degenerate_sizes_are_clamped_not_panicking() {
    let meshes = [
        Mesh::sphere(-1.0, 0, 0),
        Mesh::sphere(f32::NAN, 1, 1),
        Mesh::sphere(1.0, u32::MAX, 3),
        Mesh::torus(0.0, -0.5, 0, 0),
        Mesh::torus(0.2, 1.0, 8, 8),
        Mesh::plane(f32::INFINITY, 0),
        Mesh::cube(-3.0),
        Mesh::teapot(0),
    ];
    for mesh in &meshes {
        mesh.validate().unwrap();
    }
    assert_eq!(meshes[0].vertex_count(), 4 * 3, "at least 3 slices and 2 stacks");
    assert!(v(meshes[0].positions[4]).length() > 0.99, "a negative radius counts by its size");
    assert!(meshes[1].indices.is_empty(), "a NaN radius collapses to a point");
    assert_eq!(meshes[2].vertex_count(), (MAX_DETAIL as usize + 1) * 4);
    assert_eq!(meshes[6], Mesh::cube(3.0));
    assert_eq!(meshes[7].vertex_count(), 32 * 4);
}

#[test]
fn transformed_moves_normals_by_the_inverse_transpose() {
    let m = Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0))
        * Mat4::from_rotation_y(0.7)
        * Mat4::from_scale(Vec3::new(3.0, 1.0, 0.5));
    let mesh = Mesh::sphere(1.0, 24, 12).transformed(m);
    assert_wound_outwards(&mesh);
    for i in 0..mesh.vertex_count() {
        let n = v(mesh.normals[i]);
        assert!(n.dot(v(mesh.dpdv[i])).abs() < 1e-4, "normals stay perpendicular to the surface");
        assert!(n.dot(v(mesh.dpdu[i])).abs() < 1e-4);
    }
    let volume_ratio = volume(&mesh) / volume(&Mesh::sphere(1.0, 24, 12));
    assert!((volume_ratio - 1.5).abs() < 1e-3, "{volume_ratio}");
}

#[test]
fn mirroring_keeps_front_faces_in_front() {
    let mesh = Mesh::cube(2.0).transformed(Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0)));
    assert_wound_outwards(&mesh);
    assert!((volume(&mesh) - 8.0).abs() < 1e-5);
}

#[test]
fn a_singular_transform_gives_finite_normals() {
    let mesh = Mesh::sphere(1.0, 8, 4).transformed(Mat4::from_scale(Vec3::new(1.0, 1.0, 0.0)));
    mesh.validate().unwrap();
}

#[test]
fn validate_names_the_broken_invariant() {
    let good = Mesh::plane(1.0, 1);
    let check = |edit: &dyn Fn(&mut Mesh), expected: &str| {
        let mut mesh = good.clone();
        edit(&mut mesh);
        match mesh.validate() {
            Err(MeshError::Invalid(message)) => assert!(message.contains(expected), "{message}"),
            other => panic!("{other:?}"),
        }
    };
    check(&|m| m.uvs.truncate(3), "uvs has 3 entries for 4 positions");
    check(&|m| m.indices.push(0), "not a whole number of triangles");
    check(&|m| m.indices[4] = 9, "index 4 is 9, past the 4 vertices");
    check(&|m| m.normals[2][1] = f32::NAN, "normals[2] is not finite");
    check(&|m| m.uvs[1][0] = f32::INFINITY, "uvs[1] is not finite");
}

fn scratch(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("patina-mesh-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn obj_with_normals_and_texture_coordinates() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/models/quad.obj");
    let mesh = Mesh::load_obj(path).unwrap();
    assert_eq!(mesh.triangle_count(), 2, "the quad is triangulated");
    assert_wound_outwards(&mesh);
    for i in 0..mesh.vertex_count() {
        let [x, y, _] = mesh.positions[i];
        assert_eq!(mesh.uvs[i], [x + 0.5, 0.5 - y], "t is flipped to RenderMan's top-down");
        assert_eq!(mesh.normals[i], [0.0, 0.0, -1.0]);
        assert!(v(mesh.dpdu[i]).abs_diff_eq(Vec3::X, 1e-6));
        assert!(v(mesh.dpdv[i]).abs_diff_eq(Vec3::NEG_Y, 1e-6));
    }
}

#[test]
fn obj_without_normals_or_uvs_gets_smooth_normals_and_a_tangent_frame() {
    // A tetrahedron, wound outwards.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    let mesh = Mesh::load_obj(scratch("tetra.obj", text)).unwrap();
    assert_wound_outwards(&mesh);
    assert_derivatives_along_normals(&mesh);
    assert!(mesh.uvs.iter().all(|uv| *uv == [0.0, 0.0]));
    let origin = mesh.positions.iter().position(|p| *p == [0.0; 3]).unwrap();
    assert!(v(mesh.normals[origin]).abs_diff_eq(Vec3::splat(-1.0).normalize(), 1e-6));
    for i in 0..mesh.vertex_count() {
        let frame = v(mesh.dpdu[i]).cross(v(mesh.dpdv[i]));
        assert!(frame.abs_diff_eq(v(mesh.normals[i]), 1e-5), "dPdu × dPdv = N");
    }
}

#[test]
fn obj_errors_name_the_file_and_do_not_panic() {
    let missing = Mesh::load_obj("/nonexistent/model.obj").unwrap_err().to_string();
    assert_eq!(missing, "cannot load /nonexistent/model.obj: No such file or directory");
    let no_faces = Mesh::load_obj(scratch("points.obj", "v 0 0 0\nv 1 0 0\n")).unwrap_err().to_string();
    assert!(no_faces.ends_with("points.obj: the file has no faces"), "{no_faces}");
    for (name, text) in [
        ("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
        ("garbage.obj", "v 0 zero 0\nf 1 2 3\n"),
        ("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 NaN 0\nf 1 2 3\n"),
    ] {
        assert!(Mesh::load_obj(scratch(name, text)).is_err(), "{name}");
    }
}
