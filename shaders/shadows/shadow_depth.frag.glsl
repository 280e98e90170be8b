// Depth only: the rasterizer writes it; nothing else is needed.
void main() {}
