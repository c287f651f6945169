//! The built-in signatures. See the module documentation for the notation.
//!
//! Sources: RenderMan Interface Specification 3.2, section 15 (built-in functions), and the Stanford
//! Real-Time Shading Language as used in W. R. Mark's chapter of *Texturing & Modeling*, 3rd ed.
//! (shared/seeds/002_a44091d2843c02ac.txt, lines 3225-3850). docs/builtins.md is the readable form
//! of this table; keep the two in step.
//! Every name here has its `BuiltinId` variant (`ir/builtin.rs`); a line with a name without one
//! fails to parse.
//!
//! Left out on purpose:
//! - The notation has no untyped variadics: `printf` and `format` are listed with `float...`, and
//!   `sema/lower/call.rs` checks their values against the format's conversions instead.
//! - The optional `"name", value` arguments of `texture`, `environment`, `shadow` are not in the
//!   lines: `builtins::options` lists them and `sema/lower/call.rs` checks them after the
//!   positional arguments (`builtins::honoured_options` says which have an effect). `filterstep`
//!   takes none.
//! - `option` (answered in `sema/lower/call.rs`) and `bake` (a no-op there) are not in the lines.
//! - `trace`, `textureinfo`, message passing other than `lightsource` and `surface` (`incident`,
//!   `displacement`, ...) and renderer queries (`attribute`, `rendererinfo`): rejected by name in
//!   sema/unsupported.rs.
//! - PRMan's resizable-array functions (`arraylength`, `resize`, `push`, ...): not in RI 3.2, and
//!   Patina's arrays have a fixed size.

/// One overload (or a `for T in ...` family of overloads) per line.
pub const SIGNATURES: &[&str] = &[
    // ---------------------------------------------------------------------------------------------
    // RenderMan 15.1: mathematical functions.
    // ---------------------------------------------------------------------------------------------
    // Angles and trigonometry. RSL defines them on floats; `sin`, `cos` also apply componentwise to
    // Stanford's float3/float4 (and colours).
    "float radians(float)",
    "float degrees(float)",
    "for T in float|color|float3|float4: T sin(T)",
    "float asin(float)",
    "for T in float|color|float3|float4: T cos(T)",
    "float acos(float)",
    "float tan(float)",
    "float atan(float)",
    "float atan(float, float)",
    // Powers, exponentials and logarithms.
    "for T in float|color|float3|float4: T pow(T, T)",
    "for T in float|color|float3|float4: T exp(T)",
    "for T in float|color|float3|float4: T sqrt(T)",
    "float inversesqrt(float)",
    "for T in float|color|float3|float4: T log(T)",
    "float log(float, float)",
    // Shaping: componentwise on every numeric type where RSL or Stanford allow it.
    "float mod(float, float)",
    "for T in @numeric: T abs(T)",
    "float sign(float)",
    "for T in @numeric: T min(T, T, T...)",
    "for T in @numeric: T max(T, T, T...)",
    "for T in @numeric: T clamp(T, T, T)",
    // Scalar bounds on a vector (`clamp(flamecolor, 0, 1)` in the book's flame shader).
    "for T in @triple|float4: T clamp(T, float, float)",
    "for T in @numeric: T mix(T, T, float)",
    "for T in @numeric: T floor(T)",
    "for T in @numeric: T ceil(T)",
    "float round(float)",
    "float step(float, float)",
    "float smoothstep(float, float, float)",
    // Antialiased step: the 2-argument form filters over the derivative of its second argument.
    "float filterstep(float, float) [deriv]",
    "float filterstep(float, float, float) [deriv]",
    // Catmull-Rom (or named-basis) splines through at least four knots, listed or in an array.
    "for T in float|color|point|vector: T spline(float, T, T, T, T, T...)",
    "for T in float|color|point|vector: T spline(string, float, T, T, T, T, T...)",
    "for T in float|color|point|vector: T spline(float, T[])",
    "for T in float|color|point|vector: T spline(string, float, T[])",
    // Derivatives with respect to the surface parameters u and v (fragment rate).
    "for T in float|color|vector|normal|float3: T Du(T) [deriv]",
    "vector Du(point) [deriv]",
    "for T in float|color|vector|normal|float3: T Dv(T) [deriv]",
    "vector Dv(point) [deriv]",
    "for T in float|color|vector|normal|float3: T Deriv(T, float) [deriv]",
    "vector Deriv(point, float) [deriv]",
    // Patina extension: the filter width |Du(x) du| + |Dv(x) dv| of the antialiasing chapters.
    "float filterwidth(float) [deriv]",
    // Uniformly distributed in [0, 1), a new value at every shading point; the result type chooses.
    "float random() [fragment]",
    "color random() [fragment]",
    "point random() [fragment]",
    "vector random() [fragment]",
    // `printf` and `format` take values of any type after the format (checked against its
    // conversions by `sema/lower/call.rs`, which bypasses overload resolution for them); the
    // lines give the call its IR form.
    "void printf(string, float...)",
    "string format(string, float...)",
    // Internal: `random()` lowered where a uniform value is wanted (RSL: `uniform float x =
    // random()` is one value per primitive): the same hash, of a fixed point index instead of the
    // point's, so one value per draw.
    "float __uniform_random() [uniform]",
    "color __uniform_random() [uniform]",
    "point __uniform_random() [uniform]",
    "vector __uniform_random() [uniform]",
    // Noise in [0, 1] over 1- to 4-dimensional domains; the result type chooses the overload.
    "for T in float|color|point|vector: T noise(float)",
    "for T in float|color|point|vector: T noise(float, float)",
    "for T in float|color|point|vector: T noise(point)",
    "for T in float|color|point|vector: T noise(point, float)",
    // Signed noise in [-1, 1] (`2 * noise(x) - 1`), as Peachey defines it [TM L2681] and OSL has it.
    "for T in float|color|point|vector: T snoise(float)",
    "for T in float|color|point|vector: T snoise(float, float)",
    "for T in float|color|point|vector: T snoise(point)",
    "for T in float|color|point|vector: T snoise(point, float)",
    // Periodic noise: each domain argument followed by its period (uniform in RSL).
    "for T in float|color|point|vector: T pnoise(float, float)",
    "for T in float|color|point|vector: T pnoise(float, float, float, float)",
    "for T in float|color|point|vector: T pnoise(point, point)",
    "for T in float|color|point|vector: T pnoise(point, float, point, float)",
    // Cellular noise: constant over each unit cell of the domain.
    "for T in float|color|point|vector: T cellnoise(float)",
    "for T in float|color|point|vector: T cellnoise(float, float)",
    "for T in float|color|point|vector: T cellnoise(point)",
    "for T in float|color|point|vector: T cellnoise(point, float)",
    // ---------------------------------------------------------------------------------------------
    // RenderMan 15.2: geometric functions.
    // ---------------------------------------------------------------------------------------------
    "for T in point|vector|normal: float xcomp(T)",
    "for T in point|vector|normal: float ycomp(T)",
    "for T in point|vector|normal: float zcomp(T)",
    "for T in point|vector|normal: void setxcomp(output T, float)",
    "for T in point|vector|normal: void setycomp(output T, float)",
    "for T in point|vector|normal: void setzcomp(output T, float)",
    "for T in point|vector|normal: float length(T)",
    "for T in vector|normal: T normalize(T)",
    "vector normalize(point)",
    "float distance(point, point)",
    // Distance from the third point to the segment between the first two.
    "float ptlined(point, point, point)",
    // Rotate a point by an angle (radians) about the axis through two points.
    "point rotate(point, float, point, point)",
    "float area(point) [deriv]",
    // Flip the first argument to face against the incident vector (or with Nref's orientation).
    "for T in normal|vector: T faceforward(T, vector)",
    "for T in normal|vector: T faceforward(T, vector, T)",
    "vector reflect(vector, normal)",
    "vector refract(vector, normal, float)",
    // Fresnel reflection and transmission coefficients (Kr, Kt), optionally with the reflected
    // and transmitted directions (R, T).
    "void fresnel(vector, normal, float, output float, output float)",
    "void fresnel(vector, normal, float, output float, output float, output vector, output vector)",
    // Coordinate systems: to a named space, between two, by a matrix, or from a space by a matrix.
    // `transform` applies the rule of its argument's type (points translate, vectors do not,
    // normals use the inverse transpose); `vtransform`, `ntransform` are the spec's explicit forms.
    "for T in point|vector|normal: T transform(string, T)",
    "for T in point|vector|normal: T transform(string, string, T)",
    "for T in point|vector|normal: T transform(matrix, T)",
    "for T in point|vector|normal: T transform(string, matrix, T)",
    "vector vtransform(string, vector)",
    "vector vtransform(string, string, vector)",
    "vector vtransform(matrix, vector)",
    "vector vtransform(string, matrix, vector)",
    "normal ntransform(string, normal)",
    "normal ntransform(string, string, normal)",
    "normal ntransform(matrix, normal)",
    "normal ntransform(string, matrix, normal)",
    // Depth of a point: 0 at the near clipping plane, 1 at the far one.
    "float depth(point)",
    "normal calculatenormal(point) [deriv]",
    // ---------------------------------------------------------------------------------------------
    // RenderMan 15.3: colour functions.
    // ---------------------------------------------------------------------------------------------
    "float comp(color, float)",
    "void setcomp(output color, float, float)",
    "color ctransform(string, color)",
    "color ctransform(string, string, color)",
    // Internal: `ctransform`'s implementation (`compiler/stdlib/builtins.sl`) checks a space name
    // that is not a literal (a string parameter's value, known to the backends) with this.
    "void __colour_space(string)",
    // ---------------------------------------------------------------------------------------------
    // RenderMan 15.4: matrix functions (row, column).
    // ---------------------------------------------------------------------------------------------
    "float comp(matrix, float, float)",
    "void setcomp(output matrix, float, float, float)",
    "float determinant(matrix)",
    "matrix translate(matrix, vector)",
    "matrix rotate(matrix, float, vector)",
    "matrix scale(matrix, point)",
    // ---------------------------------------------------------------------------------------------
    // RenderMan 15.5: string functions. `printf` and `format` are left out: their further
    // arguments are of any type, and untyped variadics are not supported.
    // ---------------------------------------------------------------------------------------------
    "string concat(string, string...)",
    "float match(string, string)",
    // ---------------------------------------------------------------------------------------------
    // RenderMan 15.6: shading and lighting. The sums over lights exist only in surface shaders.
    // ---------------------------------------------------------------------------------------------
    "color ambient() [lights, surface]",
    "color diffuse(normal) [lights, surface]",
    "color specular(normal, vector, float) [lights, surface]",
    "color phong(normal, vector, float) [lights, surface]",
    // The specular term for one light (L, N, V, roughness): for hand-written illuminance loops.
    "color specularbrdf(vector, normal, vector, float)",
    // Message passing, answered by binding (the shaders are bound together): inside `illuminance`,
    // the parameter of that name of the light being visited, written to the output with 1
    // returned when the light has one of the output's type, 0 and nothing written otherwise.
    "for T in float|color|point|vector|normal: float lightsource(string, output T) [fragment, illuminance]",
    // In a light or an atmosphere (volume) shader: the parameter of that name of the surface it
    // is bound with, written to the output with 1 returned when the surface has one of the
    // output's type, 0 and nothing written otherwise.
    "for T in float|color|point|vector|normal: float surface(string, output T) [fragment, light_or_volume]",
    // ---------------------------------------------------------------------------------------------
    // RenderMan 15.7: texture mapping. The result type chooses between a channel and a colour;
    // the implicit filter region comes from screen derivatives.
    // ---------------------------------------------------------------------------------------------
    // The one-argument form reads `s` and `t` (`opt/textures.rs`): per fragment, as a lookup at
    // varying coordinates is, never at the rate of its name alone.
    "for T in float|color: T texture(string) [fragment]",
    "for T in float|color: T texture(string, float, float) [deriv]",
    // Explicit region: the four corners (s1, t1, ..., s4, t4).
    "for T in float|color: T texture(string, float, float, float, float, float, float, float, float)",
    "for T in float|color: T environment(string, vector) [deriv]",
    "for T in float|color: T environment(string, vector, vector, vector, vector)",
    "float shadow(string, point) [deriv]",
    "float shadow(string, point, point, point, point)",
    // ---------------------------------------------------------------------------------------------
    // Stanford RTSL.
    // ---------------------------------------------------------------------------------------------
    // Texture lookups, RGBA; a float3 coordinate is (s, t, r) and a float4 one is homogeneous.
    "float4 texture(texref, float4) [deriv]",
    "float4 texture(texref, float3) [deriv]",
    "float4 texture3d(texref, float4) [deriv]",
    // Internal: what `opt::textures` expands texture lookups into, so that both backends share
    // one filter (`docs/builtins.md`). A texel of a 2D or 3D texture by integer coordinates (in
    // range), and a texture's size along an axis (by dimension, so a size query declares the
    // texture as its fetches do).
    "float4 __texel2d(string, int, int)",
    "float4 __texel2d(texref, int, int)",
    "float4 __texel3d(string, int, int, int)",
    "float4 __texel3d(texref, int, int, int)",
    "int __texsize2d(string, int)",
    "int __texsize2d(texref, int)",
    "int __texsize3d(string, int)",
    "int __texsize3d(texref, int)",
    // Three- and four-vector operations.
    "float dot(float3, float3)",
    "float dot(float4, float4)",
    "float3 cross(float3, float3)",
    "float3 normalize(float3)",
    "float length(float3)",
    // The first three components.
    "float3 rgb(float4)",
    "for T in float|float3|float4: T clamp01(T)",
    // Componentwise choice, both sides evaluated.
    "for T in @numeric|bool|int|uint|matrix3|matrix4: T select(bool, T, T)",
    // Matrices: inverse, upper-left 3x3, transpose.
    "matrix4 invert(matrix4)",
    "matrix3 invert(matrix3)",
    "matrix3 affine(matrix4)",
    "matrix4 transpose(matrix4)",
    "matrix3 transpose(matrix3)",
    // Sum a perlight value over the bound lights.
    "for T in float|float3|float4|color: T integrate(T) [integrate]",
    // Window position of the fragment: x, y in pixels, z the depth, w = 1.
    "float4 xyz_screen() [fragment]",
    // ---------------------------------------------------------------------------------------------
    // Extensions: int and uint (bit operations are operators, not functions).
    // ---------------------------------------------------------------------------------------------
    "for T in int|uint: T abs(T)",
    "for T in int|uint: T min(T, T, T...)",
    "for T in int|uint: T max(T, T, T...)",
    "for T in int|uint: T clamp(T, T, T)",
];

#[cfg(test)]
mod tests {
    use super::super::builtins;
    use crate::ir::types::{Base, Type};

    #[test]
    fn no_overload_is_listed_twice() {
        let table = builtins();
        for name in table.names() {
            let overloads = table.overloads(name);
            for (i, a) in overloads.iter().enumerate() {
                for b in &overloads[i + 1..] {
                    let same = a.ret == b.ret && a.params == b.params && a.rest == b.rest;
                    assert!(!same, "`{}` and `{}` are the same overload", a.signature, b.signature);
                }
            }
        }
    }

    #[test]
    fn the_specified_forms_are_there() {
        let table = builtins();
        let has = |name: &str, sig: &str| table.overloads(name).iter().any(|b| b.signature == sig);
        assert!(has("noise", "color noise(point, float)"));
        assert!(has("pnoise", "vector pnoise(point, float, point, float)"));
        assert!(has("spline", "color spline(string, float, color[])"));
        assert!(has("transform", "normal transform(string, matrix, normal)"));
        assert!(has("texture", "float4 texture(texref, float3)"));
        assert!(has("select", "float3 select(bool, float3, float3)"));
        assert!(has("max", "uint max(uint, uint, uint...)"));
        let random = table.overloads("random");
        assert_eq!(random.len(), 4);
        assert!(random.iter().all(|b| b.rate == crate::ir::builtin::RateRule::Fragment));
        let diffuse = &table.overloads("diffuse")[0];
        assert_eq!(diffuse.context, super::super::Context::Surface);
        assert!(table.overloads("trace").is_empty() && table.overloads("option").is_empty());
        assert_eq!(table.overloads("printf")[0].ret, crate::ir::types::Type::VOID);
        assert!(
            table
                .overloads("__uniform_random")
                .iter()
                .all(|b| b.rate == crate::ir::builtin::RateRule::Uniform)
        );
        let fresnel = table.overloads("fresnel");
        assert!(fresnel.iter().any(|b| b.params.len() == 7 && b.params[6].output));
        let affine = &table.overloads("affine")[0];
        assert_eq!((affine.ret, affine.params[0].ty), (Type::of(Base::Matrix3), Type::of(Base::Matrix4)));
    }

    #[test]
    fn overload_count() {
        let table = builtins();
        let total: usize = table.names().map(|n| table.overloads(n).len()).sum();
        let names = table.names().count();
        // Printed by `cargo test -- --nocapture`; docs/builtins.md quotes it.
        println!("{names} built-in names, {total} overloads");
        assert!(names > 80 && total > 300, "{names} names, {total} overloads");
    }
}
