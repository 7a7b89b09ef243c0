// Trim mask (paper 3.4.2): a loop's polygon, (u, v) already mapped to [0, 1]^2 of the surface's
// domain on the CPU, drawn as a triangle fan from its first vertex into the mask layer.
layout(location = KW_ATTR_TRIM_CORNER) in vec2 aUnit;

void main() {
    gl_Position = vec4(2.0 * aUnit - 1.0, 0.0, 1.0);
}
