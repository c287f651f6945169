// Hart's parameterized solid textures (Hart, Carr, Kameya, Tibbitts & Coleman, "Antialiased
// Parameterized Solid Texturing", 1999; shared/seeds/004_dc0e594aa54d1617.txt L85-297, digest
// §3.1): the wood, marble, clouds and fire presets of <solid.sl> as four surface shaders, with
// the solid coordinates p = scale (object-space P - origin), diffusely shaded.
//
// `aa` 0 samples the texture at the pixel's centre (point sampling); `aa` 1 is APST's analytic
// filter: the preset's colour map box-filtered over the spread of colour indices across the
// pixel, ||grad_xy f|| = sqrt((grad f . dp/dx)^2 + (grad f . dp/dy)^2), dp/dx and dp/dy being the
// pixel's footprint in solid space (hart_pixel_dp); the noise terms finer than the footprint
// also fade to their mean. The supersampled reference is the same scene with aa 0 and
// output.supersample.

#include <solid.sl>

// The solid coordinates of the shading point (scales are modest: 1e30 times a coordinate of 1e30
// overflows f32).
// sweep: scale in [-1e4, 1e4]
point hart_solid_point(float scale; float origin[3])
{
    return scale * (transform("object", P) - point (origin[0], origin[1], origin[2]));
}

// The change of p across one pixel along the raster axis `axis` (0: x, 1: y), from Du and Dv of p
// and of the window position (the inverse of its Jacobian over (u, v)); 0 when `aa` is 0. With
// both axes it is the pixel's footprint in solid space, over which the presets filter (APST (9)).
vector hart_pixel_dp(point p; float axis, aa)
{
    point w = point (xyz_screen()[0], xyz_screen()[1], 0);
    vector wu = Du(w), wv = Dv(w);
    float det = wu[0] * wv[1] - wv[0] * wu[1];
    vector pu = Du(p), pv = Dv(p);
    vector dpdx = det != 0 ? (wv[1] * pu - wu[1] * pv) / det : vector (0);
    vector dpdy = det != 0 ? (wu[0] * pv - wv[0] * pu) / det : vector (0);
    return aa > 0.5 ? (axis < 0.5 ? dpdx : dpdy) : vector (0);
}

// Matte shading of the texture colour.
color hart_shade(color Ct; float Ka, Kd)
{
    normal Nf = faceforward(normalize(N), I);
    return Ct * (Ka * ambient() + Kd * diffuse(Nf));
}

surface
solid_wood(float aa = 1; float scale = 1; float origin[3] = {0, 0, 0}; float Ka = 0.35, Kd = 0.75)
{
    point p = hart_solid_point(scale, origin);
    Ci = hart_shade(hart_wood_footprint(p, 0, hart_pixel_dp(p, 0, aa), hart_pixel_dp(p, 1, aa)), Ka, Kd);
    Oi = 1;
}

surface
solid_marble(float aa = 1; float scale = 1; float origin[3] = {0, 0, 0}; float Ka = 0.35, Kd = 0.75)
{
    point p = hart_solid_point(scale, origin);
    Ci = hart_shade(hart_marble_footprint(p, 0, hart_pixel_dp(p, 0, aa), hart_pixel_dp(p, 1, aa)), Ka, Kd);
    Oi = 1;
}

surface
solid_clouds(float aa = 1; float scale = 1; float origin[3] = {0, 0, 0}; float Ka = 0.35, Kd = 0.75)
{
    point p = hart_solid_point(scale, origin);
    Ci = hart_shade(hart_clouds_footprint(p, 0, hart_pixel_dp(p, 0, aa), hart_pixel_dp(p, 1, aa)), Ka, Kd);
    Oi = 1;
}

surface
solid_fire(float aa = 1; float scale = 1; float origin[3] = {0, 0, 0}; float phase = 0;
           float Ka = 0.35, Kd = 0.75)
{
    point p = hart_solid_point(scale, origin);
    Ci = hart_shade(hart_fire_footprint(p, phase, 0, hart_pixel_dp(p, 0, aa), hart_pixel_dp(p, 1, aa)), Ka, Kd);
    Oi = 1;
}
