/**
 * @class   pqPointCloudBilateralReadOutWidget
 * @brief   shows an information property of the plugin's proxies as plain text in the
 *          Properties panel
 *
 * ParaView 5.11 shows an information property (information_only="1": Last Run, Radius Used,
 * Number Of Iterations Used...) with the widget of an editable one, a line edit, disabled but
 * styled to look enabled: it reads as a field to type in. This widget shows the property's
 * values as text instead (word-wrapped, so a long Last Run, a failed run's whole error, is read
 * in full), and follows the property as the proxy's information is updated after each run.
 * The XML chooses it with panel_widget="pcb_read_out". The text is the child QLabel named
 * "ReadOut" (what the GUI tests check).
 */
#ifndef pqPointCloudBilateralReadOutWidget_h
#define pqPointCloudBilateralReadOutWidget_h

#include "pqPropertyWidget.h"

class QLabel;

class pqPointCloudBilateralReadOutWidget : public pqPropertyWidget
{
  Q_OBJECT
  typedef pqPropertyWidget Superclass;

public:
  pqPointCloudBilateralReadOutWidget(vtkSMProxy* proxy,
    vtkSMProperty* property,
    QWidget* parent = nullptr);
  ~pqPointCloudBilateralReadOutWidget() override;

  /// The property's values as shown: numbers separated by spaces, strings as they are.
  static QString FormatValues(vtkSMProperty* property);

private Q_SLOTS:
  void showValues();

private:
  QLabel* Text;

  Q_DISABLE_COPY(pqPointCloudBilateralReadOutWidget)
};

#endif
