// Edge Continuity overlay: the segment's class colour. AOV targets are left untouched.
in vec4 vColor;
layout(location = 0) out vec4 fragColor;

void main() { fragColor = vColor; }
