// Depth pre-pass: no colour, the rasteriser writes the base polygon's depth.
// Trimming (later issue) must discard here too, exactly as in exact_surface.frag, or trimmed
// holes would keep their depth and hide what lies behind them under GL_EQUAL.
void main() {}
