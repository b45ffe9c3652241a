# Writes a program's manual page from its own --help and --version, so the
# two cannot differ: NAME from the help's first line ("prog: what it does"),
# SYNOPSIS from its usage block, DESCRIPTION the rest as printed (fill off,
# since the help is laid out by hand). Then gzip -9n, as Debian installs
# manual pages.
# cmake -DPROGRAM=path -DOUT=prog.1.gz -DSEE_ALSO="a;b" -P man_page.cmake
execute_process(COMMAND ${PROGRAM} --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} --help failed (${rc})")
endif()
execute_process(COMMAND ${PROGRAM} --version OUTPUT_VARIABLE version OUTPUT_STRIP_TRAILING_WHITESPACE)
get_filename_component(name ${PROGRAM} NAME)
string(REGEX REPLACE "^[^ ]+ " "" version "${version}")
string(REGEX REPLACE "\n.*" "" version "${version}")

# roff: a backslash is \e, a minus \-, and a line may not start with . or '.
function(roff text out)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REPLACE "-" "\\-" text "${text}")
  string(REGEX REPLACE "\n([.'])" "\n\\\\&\\1" text "\n${text}")
  string(SUBSTRING "${text}" 1 -1 text)
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

string(REGEX MATCH "^[^\n]*" first "${help}")
string(REGEX REPLACE "^[^:]*: *" "" summary "${first}")
string(FIND "${help}" "\nusage:\n" usage_at)
if(usage_at LESS 0)
  message(FATAL_ERROR "${PROGRAM} --help has no usage: block")
endif()
math(EXPR usage_at "${usage_at} + 8")
string(SUBSTRING "${help}" ${usage_at} -1 rest)
string(FIND "${rest}" "\n\n" end)
string(SUBSTRING "${rest}" 0 ${end} usage)
math(EXPR end "${end} + 2")
string(SUBSTRING "${rest}" ${end} -1 description)
string(REGEX REPLACE "\n+$" "" description "${description}")
# The usage lines are indented two spaces in the help. (CMake's ^ matches
# wherever a search resumes, so lines are found by their newline.)
string(REGEX REPLACE "\n  " "\n" usage "\n${usage}")
string(SUBSTRING "${usage}" 1 -1 usage)

roff("${summary}" summary)
roff("${usage}" usage)
roff("${description}" description)
string(TOUPPER "${name}" title)
string(TIMESTAMP date "%Y-%m-%d" UTC)
set(see_also "")
foreach(other IN LISTS SEE_ALSO)
  if(see_also)
    string(APPEND see_also ",\n")
  endif()
  string(APPEND see_also ".BR ${other} (1)")
endforeach()

set(page ".TH ${title} 1 \"${date}\" \"umf ${version}\" \"User Commands\"
.SH NAME
${name} \\- ${summary}
.SH SYNOPSIS
.nf
${usage}
.fi
.SH DESCRIPTION
.nf
${description}
.fi
")
if(see_also)
  string(APPEND page ".SH SEE ALSO\n${see_also}\n")
endif()
get_filename_component(out_dir ${OUT} DIRECTORY)
string(REGEX REPLACE "\\.gz$" "" plain ${OUT})
file(WRITE ${plain} "${page}")
execute_process(COMMAND gzip -9nf ${plain} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "gzip ${plain} failed")
endif()
