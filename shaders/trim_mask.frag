// Trim mask: every fan triangle writes all ones with GL_XOR as the logic op, so a texel ends up
// set when an odd number of triangles cover it (even-odd parity; orientation is irrelevant).
layout(location = KW_TRIM_MASK_OUTPUT) out vec4 maskValue;

void main() {
    maskValue = vec4(1.0);
}
