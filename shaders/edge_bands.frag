// Edge Continuity overlay: the segment's class colour. AOV targets are left untouched.
in vec4 vColor;
layout(location = KW_COLOUR_OUTPUT) out vec4 fragColor;

void main() { fragColor = vColor; }
