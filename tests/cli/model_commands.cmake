# `hbos-score fit` / `hbos-score score` end to end (examples/hbos_score/{fit,score}_command.*):
# models written and applied, CSV and .npy inputs giving identical scores, the PyOD-mode
# `score` reproducing the one-shot scorer byte for byte, and bad input refused with exit 2.
# Model files of format versions 1 and 2 are read.
# Included by tests/cli/CMakeLists.txt (hbos-score is built).
set(_data "${CMAKE_CURRENT_SOURCE_DIR}/../data/cli_model")
set(_work "${CMAKE_CURRENT_BINARY_DIR}/model_commands")
file(MAKE_DIRECTORY "${_work}")

# Runs a command and checks its exit code and standard error (model_commands_check.cmake).
function(hbos_model_command_test name exit_code stderr_regex)
  string(REPLACE ";" "|" command "${ARGN}")  # one -D argument; the script splits it again
  add_test(NAME cli:model:${name}
           COMMAND ${CMAKE_COMMAND} -DEXPECT_EXIT=${exit_code} "-DEXPECT_STDERR=${stderr_regex}"
                   "-DCOMMAND=${command}" -P ${CMAKE_CURRENT_SOURCE_DIR}/model_commands_check.cmake)
endfunction()

set(_exe $<TARGET_FILE:hbos-score>)
hbos_model_command_test(fit_default 0 "default model of 39 rows x 30 features"
                        ${_exe} fit ${_data}/wbc39.csv -o ${_work}/default.hbos)
hbos_model_command_test(fit_pyod 0 "pyod model of 39 rows x 30 features"
                        ${_exe} fit --mode pyod ${_data}/wbc39_f8.npy -o ${_work}/pyod.hbos)
hbos_model_command_test(one_shot_pyod 0 "" ${_exe} ${_data}/wbc39.csv --mode pyod -q
                        -o ${_work}/one_shot_pyod.csv)
# The one-shot form reads .npy too: C order, Fortran order and float32, each against its CSV.
foreach(input wbc39.csv wbc39_f8.npy wbc39_fortran_f8.npy wbc39_f4.npy wbc39_f4_as_f8.csv)
  hbos_model_command_test(one_shot_default_${input} 0 "" ${_exe} ${_data}/${input} -q
                          --contributions -o ${_work}/one_shot_default_${input}.csv)
  set_tests_properties(cli:model:one_shot_default_${input} PROPERTIES FIXTURES_SETUP scores)
endforeach()
hbos_model_command_test(one_shot_pyod_npy 0 "" ${_exe} ${_data}/wbc39_fortran_f8.npy --mode pyod
                        -q -o ${_work}/one_shot_pyod_npy.csv)
hbos_model_command_test(one_shot_npy_summary 0 "wbc39_f8.npy: 39 rows x 30 features \\(.npy array\\)"
                        ${_exe} ${_data}/wbc39_f8.npy -o ${_work}/one_shot_summary.csv)
hbos_model_command_test(one_shot_npy_rows 0 "\n  row [0-9]+ +score [0-9]"
                        ${_exe} ${_data}/wbc39_f8.npy -o ${_work}/one_shot_rows.csv)
set_tests_properties(cli:model:one_shot_pyod_npy PROPERTIES FIXTURES_SETUP scores)
set_tests_properties(cli:model:fit_default PROPERTIES FIXTURES_SETUP model_default)
set_tests_properties(cli:model:fit_pyod cli:model:one_shot_pyod PROPERTIES FIXTURES_SETUP model_pyod)

foreach(input wbc39.csv wbc39_f8.npy wbc39_fortran_f8.npy wbc39_f4.npy wbc39_f4_as_f8.csv)
  hbos_model_command_test(score_default_${input} 0 "" ${_exe} score ${_work}/default.hbos
                          ${_data}/${input} -o ${_work}/default_${input}.csv)
  hbos_model_command_test(score_pyod_${input} 0 "" ${_exe} score ${_work}/pyod.hbos
                          ${_data}/${input} -o ${_work}/pyod_${input}.csv)
  set_tests_properties(cli:model:score_default_${input} PROPERTIES FIXTURES_REQUIRED model_default
                       FIXTURES_SETUP scores)
  set_tests_properties(cli:model:score_pyod_${input} PROPERTIES FIXTURES_REQUIRED model_pyod
                       FIXTURES_SETUP scores)
endforeach()

# A version 1 model file (written by the release before version 2, tests/data/cli_model) is
# still read, and scores as the version 2 file fitted now.
hbos_model_command_test(score_v1_model 0 "" ${_exe} score ${_data}/wbc39_v1.hbos
                        ${_data}/wbc39.csv -o ${_work}/v1_wbc39.csv.csv)
set_tests_properties(cli:model:score_v1_model PROPERTIES FIXTURES_SETUP scores)

# Identical bytes: C order, Fortran order and CSV; float32 .npy and its exact decimals; the
# PyOD-mode model's scores and labels of its training rows and the one-shot scorer's output.
set(_same
    "default_wbc39.csv.csv default_wbc39_f8.npy.csv"
    "default_wbc39.csv.csv v1_wbc39.csv.csv"
    "default_wbc39.csv.csv default_wbc39_fortran_f8.npy.csv"
    "default_wbc39_f4.npy.csv default_wbc39_f4_as_f8.csv.csv"
    "pyod_wbc39.csv.csv pyod_wbc39_fortran_f8.npy.csv"
    "pyod_wbc39_f4.npy.csv pyod_wbc39_f4_as_f8.csv.csv"
    "one_shot_pyod.csv pyod_wbc39.csv.csv"
    "one_shot_pyod.csv one_shot_pyod_npy.csv"
    "one_shot_default_wbc39.csv.csv one_shot_default_wbc39_f8.npy.csv"
    "one_shot_default_wbc39.csv.csv one_shot_default_wbc39_fortran_f8.npy.csv"
    "one_shot_default_wbc39_f4.npy.csv one_shot_default_wbc39_f4_as_f8.csv.csv")
set(_i 0)
foreach(pair IN LISTS _same)
  separate_arguments(files UNIX_COMMAND "${pair}")
  list(GET files 0 a)
  list(GET files 1 b)
  add_test(NAME cli:model:same_${_i}
           COMMAND ${CMAKE_COMMAND} -E compare_files ${_work}/${a} ${_work}/${b})
  set_tests_properties(cli:model:same_${_i} PROPERTIES FIXTURES_REQUIRED "scores;model_pyod")
  math(EXPR _i "${_i} + 1")
endforeach()

# Bad input: exit 2 and a message naming the file and the problem.
hbos_model_command_test(truncated_npy 2 "truncated.npy: truncated .npy header"
                        ${_exe} score ${_work}/default.hbos ${_data}/truncated.npy)
hbos_model_command_test(int_npy 2 "int64.npy: dtype '<i8' is not supported"
                        ${_exe} fit ${_data}/int64.npy -o ${_work}/never.hbos)
# A CSV-only option with a .npy file is refused, not dropped: the data would not be what was asked.
hbos_model_command_test(npy_label_column 2 "wbc39_f8.npy: --label-column last is for CSV input"
                        ${_exe} fit ${_data}/wbc39_f8.npy --label-column last -o ${_work}/never.hbos)
hbos_model_command_test(npy_no_header 2 "wbc39_f8.npy: --no-header is for CSV input"
                        ${_exe} score ${_work}/default.hbos ${_data}/wbc39_f8.npy --no-header)
hbos_model_command_test(npy_one_shot_delimiter 2 "wbc39_f4.npy: --delimiter is for CSV input"
                        ${_exe} ${_data}/wbc39_f4.npy --delimiter tab -q)
hbos_model_command_test(npy_one_shot_ignore 2 "wbc39_fortran_f8.npy: --ignore-columns is for CSV input"
                        ${_exe} ${_data}/wbc39_fortran_f8.npy --ignore-columns 0 -q)
hbos_model_command_test(npy_one_shot_truncated 2 "truncated.npy: truncated .npy header"
                        ${_exe} ${_data}/truncated.npy -q)
set_tests_properties(cli:model:npy_no_header PROPERTIES FIXTURES_REQUIRED model_default)
hbos_model_command_test(damaged_model 2 "damaged.hbos', line 25 \\(hist.lo\\): '1.5x' is not a number"
                        ${_exe} score ${_data}/damaged.hbos ${_data}/wbc39.csv)
hbos_model_command_test(damaged_model_v2 2
                        "damaged_v2.hbos', line 20 \\(f.lo\\): '1.5x' is not a number"
                        ${_exe} score ${_data}/damaged_v2.hbos ${_data}/wbc39.csv)
hbos_model_command_test(missing_model 2 "cannot open model file"
                        ${_exe} score ${_work}/missing.hbos ${_data}/wbc39.csv)
hbos_model_command_test(wrong_columns 2 "fitted on 30 features but the data to score has 31"
                        ${_exe} score ${_work}/default.hbos
                        ${CMAKE_CURRENT_SOURCE_DIR}/../../examples/hbos_score/data/wbc.csv)
set_tests_properties(cli:model:truncated_npy cli:model:wrong_columns PROPERTIES
                     FIXTURES_REQUIRED model_default)
