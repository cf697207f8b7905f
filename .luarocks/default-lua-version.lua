-- LuaRocks in this checkout defaults to Lua 5.4 (lamina is a Lua 5.4 module);
-- luarocks reads this file because .luarocks/ and lua_modules/ make the
-- checkout a LuaRocks project.
return "5.4"
