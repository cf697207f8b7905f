-- LuaRocks: the Lua C module lamina.so, lamina's Lua modules (lamina.adaptive,
-- lamina.axes, ...), the shipped machine profiles and the writer plugins.
--   luarocks make --tree ./rocks            (in the checkout; Lua 5.4, see
--                                            .luarocks/default-lua-version.lua)
--   eval $(luarocks path --tree ./rocks)
--   lua5.4 -e 'local l = require "lamina"; print(#l.machines())'
-- The Makefile builds (target lua-module) and installs (install-lua). A rock
-- deploys only C modules (lib/lua/5.4) and Lua files (share/lua/5.4), so the
-- profiles go with the Lua modules (share/lua/5.4/lamina/machines) and the
-- plugins with the C module (lib/lua/5.4/lamina/plugins): the places lamina.so
-- looks beside itself in a LuaRocks tree (core/base/paths.h).
rockspec_format = "3.0"
package = "lamina"
version = "scm-1"
source = {
   url = "git+file://.",
}
description = {
   summary = "Process planning for layered manufacturing: slicing, contours, validation, machine programs",
   detailed = [[
lamina reads solid models (Unigrafix, STL, OBJ), slices them into labelled
contours, plans layers for machines described by YAML profiles and writes
their programs (LADRP, SLS, CLI, G-code, plugins). Needs the Debian packages
libyaml-dev, libembree-dev and libgeos-dev (`make deps` installs them).
]],
   license = "see LICENSE",
}
dependencies = {
   "lua >= 5.4, < 5.5",
}
build = {
   type = "make",
   build_target = "lua-module",
   build_variables = {
      LUA_CFLAGS = "-I$(LUA_INCDIR)",
      OPT = "$(CFLAGS)",
   },
   install_target = "install-lua",
   install_variables = {
      PREFIX = "$(PREFIX)",
      LUA_CMODDIR = "$(LIBDIR)",
      LUA_MODDIR = "$(LUADIR)",
      MACHINEDIR = "$(LUADIR)/lamina/machines",
      PLUGINDIR = "$(LIBDIR)/lamina/plugins",
   },
   copy_directories = {},
}
