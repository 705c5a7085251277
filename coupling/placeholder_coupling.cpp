// Placeholder until the module has its first source file; delete when it does.
namespace hdimesh { int coupling_placeholder = 0; }
