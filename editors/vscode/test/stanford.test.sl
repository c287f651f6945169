// SYNTAX TEST "source.patina" "Stanford RTSL style"
// Assertion lines (`// ^^^ scope`, `// <--- scope` for the start of a line) are read by
// vscode-tmgrammar-test, not by the grammar; each checks the source line above it.

#include <noise.sl>
// <- meta.preprocessor.include.patina keyword.control.directive.include.patina punctuation.definition.directive.patina
// <~------- keyword.control.directive.include.patina
//       ^ string.quoted.other.lt-gt.include.patina punctuation.definition.string.begin.patina
//        ^^^^^^^^ string.quoted.other.lt-gt.include.patina
#define OCTAVES 4
// <------- keyword.control.directive.define.patina
//      ^^^^^^^ meta.preprocessor.macro.patina entity.name.function.preprocessor.patina
//              ^ meta.preprocessor.macro.patina constant.numeric.integer.decimal.patina

/* A procedural flame,
   after the book's example. */
// ^^^^^ comment.block.patina
//                           ^^ comment.block.patina punctuation.definition.comment.end.patina

uint hash(uint x)
// <---- storage.type.patina
//   ^^^^ entity.name.function.patina
//        ^^^^ storage.type.patina
{
    x = (x ^ (x >> 16u)) * 0x45d9f3bu;
//         ^ keyword.operator.cross.patina
//              ^^ keyword.operator.bitwise.shift.patina
//                 ^^^ constant.numeric.integer.decimal.patina
//                         ^^^^^^^^^^ constant.numeric.integer.hexadecimal.patina
    return x ^ (x >> 16u);
//  ^^^^^^ keyword.control.patina
}

light shader float4
// <----- storage.type.shader.patina
//    ^^^^^^ storage.type.shader.patina
//           ^^^^^^ storage.type.patina
falloff(primitive group float4 lightcolor, constant float k)
// <------- entity.name.function.patina
//      ^^^^^^^^^^^^^^^ storage.modifier.rate.patina
//                      ^^^^^^ storage.type.patina
//                                         ^^^^^^^^ storage.modifier.rate.patina
{
    return lightcolor / (k * Sdist);
//                           ^^^^^ variable.language.patina
}

surface shader float4 flame(vertex float4 uv, primitive group texref tex, primitive group float t0)
// <------- storage.type.shader.patina
//      ^^^^^^ storage.type.shader.patina
//             ^^^^^^ storage.type.patina
//                    ^^^^^ entity.name.function.patina
//                          ^^^^^^ storage.modifier.rate.patina
//                                 ^^^^^^ storage.type.patina
//                                            ^^^^^^^^^^^^^^^ storage.modifier.rate.patina
//                                                            ^^^^^^ storage.type.patina
{
    constant float rate = 6.0;
//  ^^^^^^^^ storage.modifier.rate.patina
//           ^^^^^ storage.type.patina
//                        ^^^ constant.numeric.float.patina
    fragment float u0 = uv[0];
//  ^^^^^^^^ storage.modifier.rate.patina
//                        ^ punctuation.section.brackets.begin.patina
//                         ^ constant.numeric.integer.decimal.patina
    vertex float4 scaled = {uv[0] * 2, uv[1], 0, 1};
//  ^^^^^^ storage.modifier.rate.patina
//                         ^ punctuation.section.block.begin.patina
    perlight float d = max(dot(N, L), 0);
//  ^^^^^^^^ storage.modifier.rate.patina
//                     ^^^ support.function.builtin.patina
//                         ^^^ support.function.builtin.patina
//                             ^ variable.language.patina
//                                ^ variable.language.patina
    bool lower = u0 < 0.5 && !(t0 > 1.0e-3f);
//  ^^^^ storage.type.patina
//                  ^ keyword.operator.comparison.patina
//                    ^^^ constant.numeric.float.patina
//                        ^^ keyword.operator.logical.patina
//                           ^ keyword.operator.logical.patina
//                                  ^^^^^^^ constant.numeric.float.patina
    int frame = int(t0 * rate);
//  ^^^ storage.type.patina
//              ^^^ storage.type.patina
    float3 hot = {1.0, 0.6, 0.4};
//  ^^^^^^ storage.type.patina
    float4 c = integrate(Cl * d) + texture(tex, scaled) * fbm(P, OCTAVES);
//  ^^^^^^ storage.type.patina
//             ^^^^^^^^^ support.function.builtin.patina
//                       ^^ variable.language.patina
//                                 ^^^^^^^ support.function.builtin.patina
//                                                        ^^^ support.function.stdlib.patina
//                                                            ^ variable.language.patina
    matrix4 m = __modelview;
//  ^^^^^^^ storage.type.patina
//              ^^^^^^^^^^^ variable.language.patina
    matrix3 m3 = __invmodelview3;
//  ^^^^^^^ storage.type.patina
    clampf k = select(lower, 1, .5) + float(hash(uint(frame)));
//  ^^^^^^ storage.type.patina
//             ^^^^^^ support.function.builtin.patina
//                              ^^ constant.numeric.float.patina
//                                    ^^^^^ storage.type.patina
//                                          ^^^^ entity.name.function.call.patina
//                                               ^^^^ storage.type.patina
    bool yes = true, no = false;
//             ^^^^ constant.language.boolean.patina
//                        ^^^^^ constant.language.boolean.patina
    for (int i = 0; i < 4; i++) { if (i == 2) continue; else break; }
//  ^^^ keyword.control.patina
//                          ^^ keyword.operator.increment.patina
//                                ^^ keyword.control.patina
//                                      ^^ keyword.operator.comparison.patina
//                                            ^^^^^^^^ keyword.control.patina
//                                                      ^^^^ keyword.control.patina
//                                                           ^^^^^ keyword.control.patina
    return {rgb(c) * k, 1}; // the result
//  ^^^^^^ keyword.control.patina
//          ^^^ support.function.builtin.patina
//                          ^^ comment.line.double-slash.patina punctuation.definition.comment.patina
//                             ^^^^^^^^^^ comment.line.double-slash.patina
}
