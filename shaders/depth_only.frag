// Depth pre-pass: no colour, the rasteriser writes the base polygon's depth.
void main() {}
