//! The shared harness of the standard-library tests (`support/`): inputs of different widths
//! reach the same slots on both backends, and outputs come back in the order asked.

mod support;

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
    assert_eq!(program.gpu(&gpu, 2, &inputs, &["Oi", "Ci"]), cpu);
}
