# ggx_sh_quote(out text): text as one shell word, for the commands the install notes print: as it is where it holds
# only characters a shell leaves alone, else in single quotes (a quote inside written '\'').
function(ggx_sh_quote out text)
  if(text MATCHES "^[A-Za-z0-9_./:@%+,=-]+$")
    set(${out} "${text}" PARENT_SCOPE)
  else()
    string(REPLACE "'" "'\\''" q "${text}")
    set(${out} "'${q}'" PARENT_SCOPE)
  endif()
endfunction()

# ggx_pc_escape(out text): text as a pkg-config variable's value: spaces, quotes and backslashes escaped with a
# backslash, so that pkg-config keeps a path with spaces as one argument.
function(ggx_pc_escape out text)
  string(REPLACE "\\" "\\\\" e "${text}")
  string(REPLACE " " "\\ " e "${e}")
  string(REPLACE "'" "\\'" e "${e}")
  string(REPLACE "\"" "\\\"" e "${e}")
  set(${out} "${e}" PARENT_SCOPE)
endfunction()
