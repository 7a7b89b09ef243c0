// Overlays: one flat colour. AOV targets are left untouched (draw buffer 0 only).
uniform vec4 uLineColor;
layout(location = 0) out vec4 fragColor;

void main() { fragColor = uLineColor; }
