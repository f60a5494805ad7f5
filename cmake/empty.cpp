// Compiled into a module library that has no source files of its own yet.
