#version 460
// The last pass of the report's WebGL2 view (report/viewer.cpp): the resolved linear radiance of
// the shading pass to the canvas's display values through the renderer's own output transform
// (output.glsl, encode.comp's), one pixel a fragment; the canvas quantizes to 8 bits. Translated
// to ESSL 3.00 when matforge is built (cmake/WebglShader.cmake).
#include "interface.h"
#include "output.glsl"

layout(set = 0, binding = 0) uniform sampler2D radiance;  // the shaded frame, top row first (Vulkan's order)
layout(set = 0, binding = 1, std140) uniform EncodeBlock {
    EncodeParams params;
};

layout(location = 0) out vec4 out_color;

void main() {
    // The canvas's rows run bottom to top.
    ivec2 xy = ivec2(int(gl_FragCoord.x), int(params.size.y) - 1 - int(gl_FragCoord.y));
    vec3 c = output_color(texelFetch(radiance, xy, 0).rgb, params);
    out_color = vec4(clamp(c, 0.0, 1.0), 1.0);
}
