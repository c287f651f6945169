// Peachey's brick wall laid on a receding strip, point-sampled or box-filtered (T&M ch. 2,
// L1559-1620 and L2120-2141; compiler/stdlib/pattern.sl's brick and filteredbrick). The strip is
// `width` x `length` world units mapped to (s, t); the bricks keep their size in those units, so
// in the distance many bricks fall into one pixel. antialias 0 point-samples the brick at
// `samples` x `samples` stratified points of the pixel's footprint in (s, t) (the footprint is
// the parallelogram Du(x) du, Dv(x) dv that filterwidth measures): samples 1 is the aliased
// pattern, and the cost grows as samples^2 (the cost knob). antialias 1 is the exact box filter
// over the footprint's bounding box, whatever `samples` is.
#include <pattern.sl>

surface brick_filtering(float Ka = 1, Kd = 1;
                        color brickcolor = color(0.5, 0.15, 0.14);
                        color mortarcolor = color(0.5, 0.5, 0.5);
                        float antialias = 1; float samples = 1;
                        float width = 1, length = 16;
                        float brickwidth = 0.25, brickheight = 0.08, mortar = 0.02)
{
    float ss = s * width, tt = t * length;
    float inbrick = 0;
    if (antialias != 0) {
        inbrick = filteredbrick(ss, tt, filterwidth(ss), filterwidth(tt), brickwidth, brickheight, mortar);
    } else {
        float n = max(1, floor(samples));
        float dsu = Du(ss) * du, dsv = Dv(ss) * dv, dtu = Du(tt) * du, dtv = Dv(tt) * dv;
        for (float i = 0; i < n; i += 1) {
            for (float j = 0; j < n; j += 1) {
                float a = (i + 0.5) / n - 0.5, b = (j + 0.5) / n - 0.5;
                inbrick += brick(ss + a * dsu + b * dsv, tt + a * dtu + b * dtv, brickwidth, brickheight, mortar);
            }
        }
        inbrick /= n * n;
    }
    color Ct = mix(mortarcolor, brickcolor, inbrick);
    normal Nf = faceforward(normalize(N), I);
    Oi = Os;
    Ci = Os * Ct * (Ka * ambient() + Kd * diffuse(Nf));
}
