// Swatch for docs/stdlib/noise.md: flow noise, 0.5 + 0.5 * flownoise3 over (8s, 8t, 0.5):
// the left half at angle 0 (snoise3 itself), the right half with the gradients turned by 1.5.
#include <noise.sl>

surface noise_flow_swatch(float scale = 8)
{
    float angle = s < 0.5 ? 0 : 1.5;
    Ci = 0.5 + 0.5 * flownoise3(point(scale * s, scale * t, 0.5), angle);
    Oi = 1;
}
