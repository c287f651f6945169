//! Internals of mesh construction; the shapes themselves are tested through the public API in
//! `runtime/tests/renderer/mesh.rs`.

use super::*;

#[test]
fn grid_drops_triangles_with_repeated_corners() {
    // A cone: the whole v = 1 row collapses onto the apex.
    let mesh = Mesh::grid(4, 2, |u, v| {
        let (s, c) = (std::f32::consts::TAU * u).sin_cos();
        let r = 1.0 - v;
        SurfacePoint {
            p: if v == 1.0 { Vec3::Z } else { Vec3::new(r * c, r * s, v) },
            n: Vec3::Z,
            dpdu: Vec3::X,
            dpdv: Vec3::Y,
        }
    });
    assert_eq!(mesh.vertex_count(), 5 * 3);
    assert_eq!(mesh.triangle_count(), 2 * 4 * 2 - 4);
    mesh.validate().unwrap();
}

#[test]
fn sizes_and_counts_are_made_usable() {
    assert_eq!(clamp_count(0, 3), 3);
    assert_eq!(clamp_count(u32::MAX, 3), MAX_DETAIL);
    assert_eq!(length(-2.0), 2.0);
    assert_eq!(length(f32::NAN), 0.0);
    assert_eq!(length(f32::NEG_INFINITY), 0.0);
}

#[test]
fn errors_read_as_one_line() {
    let e = MeshError::Load { path: "m.obj".into(), message: "face parse error".into() };
    assert_eq!(e.to_string(), "cannot load m.obj: face parse error");
    assert_eq!(MeshError::Invalid("x".into()).to_string(), "invalid mesh: x");
}

#[test]
fn bounds_of_an_empty_mesh_are_none() {
    assert_eq!(Mesh::default().bounds(), None);
    assert_eq!(Mesh::cube(2.0).bounds(), Some((Vec3::splat(-1.0), Vec3::ONE)));
}
