# Writes ${OUT} with the source tree's short commit, + "-dirty-<hash>" when the tree differs from
# it (tracked changes or untracked files other than results/, which no build reads): the hash
# covers the diff and the untracked files' names and contents, so two builds of different
# uncommitted sources never name the same commit (a run's identity includes it). Rewritten only
# when it changed, so that unchanged builds stay up to date.
execute_process(COMMAND git -C ${SRC} rev-parse --short=12 HEAD
  OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE failed)
if(failed OR NOT commit)
  set(commit "unknown")
else()
  execute_process(COMMAND git -C ${SRC} diff --binary HEAD -- . ":(exclude)results"
    OUTPUT_VARIABLE diff ERROR_QUIET)
  execute_process(COMMAND git -C ${SRC} ls-files --others --exclude-standard -- . ":(exclude)results"
    OUTPUT_VARIABLE untracked ERROR_QUIET)
  if(NOT "${diff}" STREQUAL "" OR NOT "${untracked}" STREQUAL "")
    set(fingerprint "${diff}")
    string(REPLACE "\n" ";" untracked_list "${untracked}")
    foreach(file ${untracked_list})
      if(NOT "${file}" STREQUAL "" AND EXISTS "${SRC}/${file}" AND NOT IS_DIRECTORY "${SRC}/${file}")
        file(SHA256 "${SRC}/${file}" file_hash)
        string(APPEND fingerprint "\n${file} ${file_hash}")
      endif()
    endforeach()
    string(SHA256 hash "${fingerprint}")
    string(SUBSTRING "${hash}" 0 8 hash)
    set(commit "${commit}-dirty-${hash}")
  endif()
endif()
set(text "#define RTBENCH_GIT_COMMIT \"${commit}\"\n")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT "${old}" STREQUAL "${text}")
  file(WRITE ${OUT} "${text}")
endif()
