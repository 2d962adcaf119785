// Placeholder translation unit until the renderer lands.
namespace sylva {}
