//! The shared harness of the standard-library tests (`support/`): inputs of different widths
//! reach the same slots on both backends, and outputs come back in the order asked.

use crate::support;

#[test]
fn both_backends_see_the_same_named_inputs() {
    let program = support::program(
        "surface t(varying float k = 0) { Ci = color(xcomp(P) + 10 * k, ycomp(P) * k, zcomp(P)); Oi = k; }",
    );
    let p = [1.0, 2.0, 3.0, -4.0, 0.5, 6.0];
    let k = [2.0, -1.0];
    let inputs = [("P", &p[..]), ("k", &k[..])];
    let cpu = program.cpu::<f64>(2, &inputs, &["Oi", "Ci"]);
    assert_eq!(cpu, [vec![2.0, 2.0, 2.0, -1.0, -1.0, -1.0], vec![21.0, 4.0, 3.0, -14.0, -0.5, 6.0]]);
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    assert_eq!(program.gpu(gpu, 2, &inputs, &["Oi", "Ci"]), cpu);
}

#[test]
fn parameters_not_given_take_their_defaults_and_pi_is_pi_on_both() {
    // The kernel sets what the interpreter sets before the inputs: defaults (in declaration order,
    // so a default may use an earlier parameter) and the predefined constants.
    let program = support::program(
        "surface t(uniform float k = 2; uniform float j = k * 3; varying float m = 5) { Ci = color(k, j, m); Oi = PI; }",
    );
    let m = [7.0];
    let inputs = [("m", &m[..])];
    let cpu = program.cpu::<f32>(1, &inputs, &["Ci", "Oi"]);
    let pi = f64::from(std::f32::consts::PI);
    assert_eq!(cpu, [vec![2.0, 6.0, 7.0], vec![pi; 3]]);
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    assert_eq!(program.gpu(gpu, 1, &inputs, &["Ci", "Oi"]), cpu);
}

#[test]
fn open_length_array_parameters_take_the_arguments_length() {
    let program = support::program(
        "float pick(float t[]; float x) { return t[x] + 10 * t[2]; }\n\
         surface s(varying float x = 0; uniform float tab[4] = {1, 2, 3, 4}; uniform float six[6] = {9, 8, 7, 6, 5, 4}) {\n\
             Ci = color(pick(tab, x), pick(six, x), 0);\n\
         }",
    );
    let x = [0.0, 1.0, 3.0, 5.0];
    let inputs = [("x", &x[..])];
    let cpu = program.cpu::<f32>(4, &inputs, &["Ci"]);
    // Indices clamp to the array: x = 5 reads tab[3].
    assert_eq!(cpu[0], [31.0, 79.0, 0.0, 32.0, 78.0, 0.0, 34.0, 76.0, 0.0, 34.0, 74.0, 0.0]);
    let Some(gpu) = patina_runtime::gpu::for_tests() else { return };
    assert_eq!(program.gpu(gpu, 4, &inputs, &["Ci"]), cpu);
}
