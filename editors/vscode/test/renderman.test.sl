// SYNTAX TEST "source.patina" "RenderMan SL style"
// Assertion lines (`// ^^^ scope`, `// <--- scope` for the start of a line) are read by
// vscode-tmgrammar-test, not by the grammar; each checks the source line above it.

#include "patterns.sl"
// <~------- keyword.control.directive.include.patina
//       ^^^^^^^^^^^^^ meta.preprocessor.include.patina string.quoted.double.patina
#define SQ(x) ((x) * (x))
// <~------ keyword.control.directive.define.patina
//      ^^ entity.name.function.preprocessor.patina
//         ^ variable.parameter.preprocessor.patina
#define NAME(a) #a
//      ^^^^ entity.name.function.preprocessor.patina
//              ^ meta.preprocessor.macro.patina keyword.operator.stringify.patina
#if defined(FAST) && LEVEL > 2
// <~-- keyword.control.directive.conditional.patina
//  ^^^^^^^ keyword.control.directive.conditional.defined.patina
//                ^^ meta.preprocessor.conditional.patina keyword.operator.logical.patina
#error too fast
// <~----- keyword.control.directive.diagnostic.patina
//     ^^^^^^^^ string.unquoted.message.patina
#endif
// <~----- keyword.control.directive.conditional.patina
#pragma once
// <~------ keyword.control.directive.patina

float accumulate(output varying float sum; uniform float x) { sum += x; return sum; }
// <----- storage.type.patina
//    ^^^^^^^^^^ entity.name.function.patina
//               ^^^^^^ storage.modifier.patina
//                      ^^^^^^^ storage.modifier.rate.patina
//                                       ^ punctuation.terminator.statement.patina
//                                         ^^^^^^^ storage.modifier.rate.patina
//                                                                ^^ keyword.operator.assignment.compound.patina

surface
plastic(float Ka = 1, Kd = .5, Ks = 0.5; float roughness = 0.1; color specularcolor = 1;
// <------- entity.name.function.patina
//                         ^^ constant.numeric.float.patina
//                                                              ^^^^^ storage.type.patina
        string texname = "")
//      ^^^^^^ storage.type.patina
//                       ^^ string.quoted.double.patina
{
    normal Nf = faceforward(normalize(N), I);
//  ^^^^^^ storage.type.patina
//              ^^^^^^^^^^^ support.function.builtin.patina
//                          ^^^^^^^^^ support.function.builtin.patina
//                                    ^ variable.language.patina
//                                        ^ variable.language.patina
    vector V = -normalize(I);
//  ^^^^^^ storage.type.patina
//             ^ keyword.operator.arithmetic.patina
    point o = point "shader" (0, 0, 0);
//  ^^^^^ storage.type.patina
//            ^^^^^ storage.type.patina
//                  ^^^^^^^^ string.quoted.double.patina
    color c = color "hsv" (.5, 1, 1) + color noise(P * 4) + texture(texname[1], s, t);
//  ^^^^^ storage.type.patina
//            ^^^^^ storage.type.patina
//                                     ^^^^^ storage.type.patina
//                                           ^^^^^ support.function.builtin.patina
//                                                 ^ variable.language.patina
//                                                          ^^^^^^^ support.function.builtin.patina
//                                                                              ^ variable.language.patina
//                                                                                 ^ variable.language.patina
    matrix m = (1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1);
//  ^^^^^^ storage.type.patina
//               ^ punctuation.separator.delimiter.patina
    uniform float k = 1e3 + 2E+10 + 3.0f + 1f + 1. + 0x1F + 7u + 1.2.3 + 12abc;
//                    ^^^ constant.numeric.float.patina
//                          ^^^^^ constant.numeric.float.patina
//                                  ^^^^ constant.numeric.float.patina
//                                         ^^ constant.numeric.float.patina
//                                              ^^ constant.numeric.float.patina
//                                                   ^^^^ constant.numeric.integer.hexadecimal.patina
//                                                          ^^ constant.numeric.integer.decimal.patina
//                                                               ^^^^^ invalid.illegal.numeric.patina
//                                                                       ^^^^^ invalid.illegal.numeric.patina
    float d = (Nf . V) * length(dPdu ^ dPdv) + SQ(du) + dv + u + v + PI / 2;
//                ^ keyword.operator.dot.patina
//                       ^^^^^^ support.function.builtin.patina
//                              ^^^^ variable.language.patina
//                                   ^ keyword.operator.cross.patina
//                                             ^^ entity.name.function.call.patina
//                                                ^^ variable.language.patina
//                                                      ^^ variable.language.patina
//                                                                   ^^ variable.language.patina
    illuminance(P, Nf, PI / 2) {
//  ^^^^^^^^^^^ keyword.control.light.patina
        Ci += Cl * (L . Nf) / (L . L);
//      ^^ variable.language.patina
//            ^^ variable.language.patina
//                  ^ variable.language.patina
    }
    printf("%f done\n", d);
//  ^^^^^^ support.function.builtin.patina
//          ^^ string.quoted.double.patina constant.other.placeholder.patina
//                 ^^ string.quoted.double.patina constant.character.escape.patina
    Oi = Os;
//  ^^ variable.language.patina
//       ^^ variable.language.patina
    Ci = Oi * Cs * (Ka * ambient() + Kd * diffuse(Nf)) + specularcolor * Ks * specular(Nf, V, roughness);
//            ^^ variable.language.patina
//                       ^^^^^^^ support.function.builtin.patina
//                                        ^^^^^^^ support.function.builtin.patina
//                                                                            ^^^^^^^^ support.function.builtin.patina
    switch (d) { }
//  ^^^^^^ invalid.illegal.reserved.patina
}

light spotlight(float intensity = 1; point from = point "shader" (0, 0, 0); vector dir = (0, 0, 1))
// <----- storage.type.shader.patina
//    ^^^^^^^^^ entity.name.function.patina
{
    illuminate(from, dir, radians(30)) { Cl = intensity * smoothstep(0.5, 0.9, L . dir); }
//  ^^^^^^^^^^ keyword.control.light.patina
//                        ^^^^^^^ support.function.builtin.patina
//                                                        ^^^^^^^^^^ support.function.builtin.patina
    solar(dir, 0) Cl += shadow("map", Ps);
//  ^^^^^ keyword.control.light.patina
//                      ^^^^^^ support.function.builtin.patina
//                                    ^^ variable.language.patina
}

displacement bumpy(float Km = 0.1) { P += Km * snoise(P) * normalize(N); N = calculatenormal(P); }
// <------------ storage.type.shader.patina
//           ^^^^^ entity.name.function.patina
//                                             ^^^^^^ support.function.builtin.patina
//                                                                           ^^^^^^^^^^^^^^^ support.function.builtin.patina

volume fog(color background = 0) { Ci = mix(Ci, background, 1 - exp(-length(I) / 10)); }
// <------ storage.type.shader.patina
//                                      ^^^ support.function.builtin.patina

imager grade(float gain = 1) { Ci *= gain; alpha = clamp(alpha, 0, 1); }
// <------ storage.type.shader.patina
//                                ^^ keyword.operator.assignment.compound.patina
//                                         ^^^^^ variable.language.patina
//                                                 ^^^^^ support.function.builtin.patina

void helper(extern float x) { }
// <---- storage.type.patina
//          ^^^^^^ storage.modifier.patina
