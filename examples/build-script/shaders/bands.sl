// Included by banded.sl: editing this file rebuilds the crate (cargo:rerun-if-changed).
float band(float x; float count) {
    return mod(floor(x * count), 2);
}
