// Placeholder until the module has its first source file; delete when it does.
namespace hdimesh { int surface_placeholder = 0; }
